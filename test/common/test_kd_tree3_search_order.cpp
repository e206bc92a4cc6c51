// KdTree3's search (iterative, with a recursive fallback for very deep trees) against brute force: on a tree
// deeper than the iterative search's stack (points at exponentially shrinking spacing: every middle split
// cuts off one point) and on a shallow, clustered one, the k nearest within the bound, nearest first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cosmo/common/kd_tree3.hpp"

using namespace cosmo;

namespace {
std::vector<float> bruteForceD2(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& q, int k,
                                double max_dist) {
  std::vector<float> d2;
  const Eigen::Vector3f qf = q.cast<float>();
  for (const auto& p : pts) {
    const Eigen::Vector3f d = qf - p.cast<float>();
    float v = 0.0f;
    v += d.x() * d.x();
    v += d.y() * d.y();
    v += d.z() * d.z();
    if (v <= static_cast<float>(max_dist * max_dist)) d2.push_back(v);
  }
  std::sort(d2.begin(), d2.end());
  if (static_cast<int>(d2.size()) > k) d2.resize(static_cast<std::size_t>(k));
  return d2;
}

void expectMatches(const KdTree3& tree, const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& q, int k,
                   double max_dist) {
  KnnResult r;
  r.reset(k, max_dist);
  tree.search(q, r);
  const std::vector<float> expected = bruteForceD2(pts, q, k, max_dist);
  ASSERT_EQ(r.size(), static_cast<int>(expected.size()));
  for (int i = 0; i < r.size(); ++i) {
    EXPECT_EQ(r.squaredDistance(i), expected[static_cast<std::size_t>(i)]);
    const Eigen::Vector3f d = q.cast<float>() - pts[r.index(i)].cast<float>();
    float v = 0.0f;
    v += d.x() * d.x();
    v += d.y() * d.y();
    v += d.z() * d.z();
    EXPECT_EQ(v, r.squaredDistance(i));
  }
}
}  // namespace

TEST(KdTree3Search, VeryDeepTreeUsesTheUnboundedSearch) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 300; ++i) pts.push_back({std::ldexp(1.0, -i / 3) * (1.0 + 0.1 * (i % 3)), 0.0, 0.0});
  KdTree3 tree;
  tree.build(pts);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-0.1, 1.5);
  for (int t = 0; t < 200; ++t) expectMatches(tree, pts, {u(rng), 0.01 * u(rng), 0.0}, 1 + t % 9, 0.05 + u(rng));
}

TEST(KdTree3Search, ClusteredPointsAllKAndBounds) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-30.0, 30.0), s(-0.5, 0.5);
  std::vector<Eigen::Vector3d> pts;
  for (int c = 0; c < 200; ++c) {
    const Eigen::Vector3d centre(u(rng), u(rng), 0.05 * u(rng));
    for (int i = 0; i < 50; ++i) pts.push_back(centre + Eigen::Vector3d(s(rng), s(rng), 0.1 * s(rng)));
  }
  KdTree3 tree;
  tree.build(pts);
  for (int t = 0; t < 2000; ++t) {
    const Eigen::Vector3d q(u(rng), u(rng), 0.05 * u(rng));
    expectMatches(tree, pts, q, 1 + t % KnnResult::kMaxK, t % 2 ? 4.0 : 0.7);
  }
}

TEST(KdTree3Search, BuildOrderDoesNotChangeTheAnswers) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 5000; ++i) pts.push_back({u(rng), u(rng), 0.1 * u(rng)});
  pts.push_back({std::nan(""), 0.0, 0.0});
  KdTree3 plain, reordered, bad;
  plain.build(pts);
  std::vector<std::uint32_t> order;
  plain.treeOrder(order);  // the finite points only
  EXPECT_EQ(order.size(), pts.size() - 1);
  std::reverse(order.begin(), order.end());
  reordered.build(pts, order);
  bad.build(pts, {0, 0, 1});  // not a permutation: ignored
  for (int t = 0; t < 1000; ++t) {
    const Eigen::Vector3d q(u(rng), u(rng), 0.1 * u(rng));
    for (const KdTree3* tree : {&reordered, &bad}) {
      KnnResult a, b;
      a.reset(5, 3.0);
      b.reset(5, 3.0);
      plain.search(q, a);
      tree->search(q, b);
      ASSERT_EQ(a.size(), b.size());
      for (int i = 0; i < a.size(); ++i) EXPECT_EQ(a.squaredDistance(i), b.squaredDistance(i));
    }
  }
}
