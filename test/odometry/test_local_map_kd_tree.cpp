// KdTree3 / LocalFeatureMap neighbour queries against brute force: the k nearest within the distance bound,
// nearest first, on clustered and degenerate (coplanar, duplicated, non-finite) point sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "cosmo/common/kd_tree3.hpp"
#include "cosmo/odometry/local_feature_map.hpp"

using namespace cosmo;

namespace {
/// Indices of the k nearest points within max_dist (squared distances in float, as the tree computes them).
std::vector<std::size_t> bruteForce(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& q, int k,
                                    double max_dist) {
  std::vector<std::pair<float, std::size_t>> all;
  const Eigen::Vector3f qf = q.cast<float>();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts[i].allFinite()) continue;
    const Eigen::Vector3f d = qf - pts[i].cast<float>();
    float d2 = 0.0f;
    d2 += d.x() * d.x();
    d2 += d.y() * d.y();
    d2 += d.z() * d.z();
    if (d2 <= static_cast<float>(max_dist * max_dist)) all.push_back({d2, i});
  }
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < all.size() && static_cast<int>(i) < k; ++i) out.push_back(all[i].second);
  return out;
}

/// Squared distances of the listed points: compared instead of indices (ties may be ordered either way).
std::vector<float> distances(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& q,
                             const std::vector<std::size_t>& idx) {
  std::vector<float> d;
  for (std::size_t i : idx) d.push_back(static_cast<float>((q - pts[i]).squaredNorm()));
  return d;
}
}  // namespace

TEST(KdTree3, MatchesBruteForceOnClusteredPoints) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-20.0, 20.0), small(-0.3, 0.3);
  std::vector<Eigen::Vector3d> pts;
  for (int c = 0; c < 60; ++c) {  // surface-like clusters plus a flat ground
    const Eigen::Vector3d centre(u(rng), u(rng), 0.1 * u(rng));
    for (int i = 0; i < 80; ++i) pts.push_back(centre + Eigen::Vector3d(small(rng), small(rng), small(rng)));
  }
  for (int i = 0; i < 3000; ++i) pts.push_back({u(rng), u(rng), -1.8});
  for (int i = 0; i < 50; ++i) pts.push_back(pts[static_cast<std::size_t>(i) * 7]);  // exact duplicates
  pts.push_back({std::nan(""), 0.0, 0.0});
  pts.push_back({std::numeric_limits<double>::infinity(), 1.0, 1.0});
  KdTree3 tree;
  tree.build(pts);
  ASSERT_EQ(tree.size(), pts.size());
  std::vector<std::size_t> idx;
  for (int trial = 0; trial < 3000; ++trial) {
    const Eigen::Vector3d q = trial % 2
                                  ? pts[static_cast<std::size_t>(trial) % 7000] + Eigen::Vector3d(small(rng), 0.0, 0.0)
                                  : Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
    const int k = 1 + trial % 8;
    const double max_dist = trial % 3 == 0 ? 0.2 : 4.0;
    tree.knn(q, k, max_dist, idx);
    const auto expected = bruteForce(pts, q, k, max_dist);
    ASSERT_EQ(idx.size(), expected.size()) << "trial " << trial;
    EXPECT_EQ(distances(pts, q, idx), distances(pts, q, expected)) << "trial " << trial;
    for (std::size_t i = 0; i < idx.size(); ++i) EXPECT_TRUE(pts[idx[i]].allFinite());
  }
}

TEST(KdTree3, EmptyAndTinyInputs) {
  KdTree3 tree;
  std::vector<std::size_t> idx{1, 2};
  tree.knn({0, 0, 0}, 5, 10.0, idx);
  EXPECT_TRUE(idx.empty());
  tree.build({{1, 0, 0}, {0, 2, 0}});
  tree.knn({0, 0, 0}, 5, 10.0, idx);
  ASSERT_EQ(idx.size(), 2u);
  EXPECT_EQ(idx[0], 0u);
  EXPECT_EQ(idx[1], 1u);
  tree.knn({0, 0, 0}, 5, 1.5, idx);
  ASSERT_EQ(idx.size(), 1u);
  tree.knn({0, 0, 0}, 0, 10.0, idx);
  EXPECT_TRUE(idx.empty());
  std::vector<Eigen::Vector3d> same(100, Eigen::Vector3d(1, 1, 1));  // all identical: no infinite split
  tree.build(same);
  tree.knn({1, 1, 1}, 5, 0.1, idx);
  EXPECT_EQ(idx.size(), 5u);
}

TEST(KdTree3, UnboundedSearchFindsEveryPointOnce) {
  // Leaves are stored in blocks of four padded with dummy points: an infinite distance bound must not let a
  // padding point in (7, 13 and 61 points leave partial blocks).
  for (const int n : {7, 13, 61}) {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < n; ++i) pts.push_back({0.5 * i, 0.25 * (i % 3), -0.1 * (i % 5)});
    KdTree3 tree;
    tree.build(pts);
    std::vector<std::size_t> idx;
    tree.knn({0.0, 0.0, 0.0}, KnnResult::kMaxK, std::numeric_limits<double>::infinity(), idx);
    ASSERT_EQ(idx.size(), static_cast<std::size_t>(std::min(n, KnnResult::kMaxK))) << n << " points";
    const auto expected = bruteForce(pts, {0.0, 0.0, 0.0}, KnnResult::kMaxK, std::numeric_limits<double>::infinity());
    EXPECT_EQ(distances(pts, {0.0, 0.0, 0.0}, idx), distances(pts, {0.0, 0.0, 0.0}, expected)) << n << " points";
    std::vector<std::size_t> sorted = idx;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << n << " points: a point found twice";
  }
}

TEST(LocalFeatureMap, NeighboursComeFromTheLastKScans) {
  odometry::LocalFeatureMap map(2);
  for (int s = 0; s < 3; ++s) map.add({Eigen::Vector3d(s, 0, 0)}, {Eigen::Vector3d(0, s, 0)});
  EXPECT_EQ(map.numScans(), 2u);
  EXPECT_EQ(map.numEdgePoints(), 2u);
  std::vector<Eigen::Vector3d> nb;
  map.nearestEdges({0, 0, 0}, 5, 10.0, nb);  // scan 0 was dropped
  ASSERT_EQ(nb.size(), 2u);
  EXPECT_EQ(nb[0], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(nb[1], Eigen::Vector3d(2, 0, 0));
  map.nearestPlanes({0, 2.2, 0}, 1, 10.0, nb);
  ASSERT_EQ(nb.size(), 1u);
  EXPECT_EQ(nb[0], Eigen::Vector3d(0, 2, 0));
  map.clear();
  map.nearestPlanes({0, 0, 0}, 5, 10.0, nb);
  EXPECT_TRUE(nb.empty());
}
