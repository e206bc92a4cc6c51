// Hash-grid neighbour pairs against brute force (same pair set, each pair once, same squared distances), on
// a seeded random cloud with negative coordinates, cell-boundary points and duplicates; and the fast features
// built on them are deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <utility>

#include <Eigen/Geometry>  // cross()

#include "cosmo/registration/fast_features.hpp"
#include "cosmo/registration/neighbour_pairs.hpp"

using namespace cosmo;

namespace {
std::vector<Eigen::Vector3f> randomCloud(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-6.f, 6.f);
  std::vector<Eigen::Vector3f> pts;
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), 0.5f * u(rng));
  pts.emplace_back(1.5f, 0.f, 0.f);  // exactly on cell boundaries (radius 1.5)
  pts.emplace_back(0.f, 0.f, 0.f);
  pts.emplace_back(-1.5f, 0.f, 0.f);
  pts.push_back(pts[3]);  // a duplicate point
  return pts;
}
}  // namespace

TEST(NeighbourPairs, MatchesBruteForce) {
  const auto pts = randomCloud(1500, 7);
  for (const float radius : {0.9f, 1.5f}) {
    const registration::NeighbourPairs pairs = registration::findNeighbourPairs(pts, radius);
    std::set<std::pair<std::uint32_t, std::uint32_t>> got;
    for (std::size_t e = 0; e < pairs.size(); ++e) {
      const std::uint32_t i = pairs[e].first, j = pairs[e].second;
      ASSERT_NE(i, j);
      EXPECT_TRUE(got.insert({std::min(i, j), std::max(i, j)}).second) << "pair listed twice";
      EXPECT_NEAR(pairs[e].squared_distance, (pts[i] - pts[j]).squaredNorm(), 1e-5f);
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> want;
    for (std::uint32_t i = 0; i < pts.size(); ++i)
      for (std::uint32_t j = i + 1; j < pts.size(); ++j) {
        const Eigen::Vector3f d = pts[j] - pts[i];
        if (d.x() * d.x() + d.y() * d.y() + d.z() * d.z() < radius * radius) want.insert({i, j});
      }
    EXPECT_EQ(got, want) << "radius " << radius;
    EXPECT_GT(want.size(), 1000u);
  }
}

TEST(NeighbourPairs, CellOrderNumberingIsTheSameSequence) {
  auto pts = randomCloud(1500, 9);
  pts.emplace_back(std::nanf(""), 0.f, 0.f);  // no position in the grid
  const registration::NeighbourPairs plain = registration::findNeighbourPairs(pts, 1.5f);
  std::vector<std::uint32_t> order;
  const registration::NeighbourPairs numbered = registration::findNeighbourPairs(pts, 1.5f, order);
  EXPECT_EQ(order.size(), pts.size() - 1);
  std::vector<int> seen(pts.size(), 0);
  for (const std::uint32_t i : order) {
    ASSERT_LT(i, pts.size());
    EXPECT_EQ(seen[i]++, 0) << "input index listed twice";
  }
  ASSERT_EQ(numbered.size(), plain.size());
  for (std::size_t e = 0; e < plain.size(); ++e) {
    ASSERT_LT(numbered[e].first, order.size());
    ASSERT_LT(numbered[e].second, order.size());
    EXPECT_EQ(order[numbered[e].first], plain[e].first);
    EXPECT_EQ(order[numbered[e].second], plain[e].second);
    EXPECT_EQ(numbered[e].squared_distance, plain[e].squared_distance);
  }
}

TEST(NeighbourPairs, EmptyAndSingle) {
  EXPECT_EQ(registration::findNeighbourPairs({}, 1.f).size(), 0u);
  EXPECT_EQ(registration::findNeighbourPairs({Eigen::Vector3f(1, 2, 3)}, 1.f).size(), 0u);
}

TEST(FastFeatures, Deterministic) {
  const auto pts = randomCloud(3000, 11);
  registration::FastFeatureParams p;
  p.keypoint_voxel = 0.9;
  const registration::FastFeatures a = computeFastFeatures(pts, p), b = computeFastFeatures(pts, p);
  ASSERT_EQ(a.kept, b.kept);
  ASSERT_EQ(a.keypoints, b.keypoints);
  ASSERT_GT(a.keypoints.size(), 10u);
  EXPECT_TRUE((a.features.array() == b.features.array()).all());
  // Each of the three sub-histograms sums to 100.
  for (Eigen::Index c = 0; c < a.features.cols(); ++c)
    for (int s = 0; s < 3; ++s) EXPECT_NEAR(a.features.col(c).segment<11>(s * 11).sum(), 100.f, 1e-2f);
}

namespace {
/// Reference FPFH, straight from the definition (O(n^2), PCL's pair feature with std::atan2), at keypoints
/// given by the tested implementation and with its normals (normal estimation is not what is compared here).
Eigen::VectorXf referenceFpfh(const std::vector<Eigen::Vector3f>& pts, const std::vector<Eigen::Vector3f>& nrm,
                              const std::vector<char>& valid, std::size_t i, float rs, float rf) {
  auto bin = [](float x, float lo, float hi) {
    const int b = static_cast<int>(std::floor(11.f * (x - lo) / (hi - lo)));
    return std::clamp(b, 0, 10);
  };
  auto spfh = [&](std::size_t p) {
    Eigen::VectorXf h = Eigen::VectorXf::Zero(33);
    int k = 0;
    for (std::size_t q = 0; q < pts.size(); ++q) {
      if (q == p || !valid[q] || (pts[q] - pts[p]).norm() > rs) continue;
      Eigen::Vector3f d = pts[q] - pts[p];
      const float len = d.norm();
      if (len == 0.f) continue;
      d /= len;
      Eigen::Vector3f u = nrm[p], nb = nrm[q];
      float f3 = u.dot(d);
      if (std::acos(std::fabs(nrm[p].dot(d))) > std::acos(std::fabs(nrm[q].dot(d)))) {
        u = nrm[q], nb = nrm[p], d = -d;
        f3 = u.dot(d);
      }
      Eigen::Vector3f v = d.cross(u);
      if (v.norm() == 0.f) continue;
      v.normalize();
      const Eigen::Vector3f w = u.cross(v);
      const float f2 = v.dot(nb), f1 = std::atan2(w.dot(nb), u.dot(nb));
      ++h(bin(f1, -float(M_PI), float(M_PI))), ++h(11 + bin(f2, -1.f, 1.f)), ++h(22 + bin(f3, -1.f, 1.f));
      ++k;
    }
    return k > 0 ? Eigen::VectorXf(h * (100.f / k)) : h;
  };
  Eigen::VectorXf acc = Eigen::VectorXf::Zero(33);
  int k = 0;
  for (std::size_t q = 0; q < pts.size(); ++q) {
    const float d = (pts[q] - pts[i]).norm();
    if (q == i || !valid[q] || d > rf || d == 0.f) continue;
    acc += spfh(q) / d;
    ++k;
  }
  if (k > 0) acc /= static_cast<float>(k);
  acc += spfh(i);
  for (int s = 0; s < 3; ++s) {
    const float sum = acc.segment<11>(s * 11).sum();
    if (sum > 0.f) acc.segment<11>(s * 11) *= 100.f / sum;
  }
  return acc;
}
}  // namespace

TEST(FastFeatures, MatchDefinition) {
  // A scene of planes and a box corner (well-defined normals) plus scattered points.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 4.f), noise(-0.02f, 0.02f);
  std::vector<Eigen::Vector3f> pts;
  for (int k = 0; k < 700; ++k) pts.emplace_back(u(rng), u(rng), noise(rng));               // ground
  for (int k = 0; k < 400; ++k) pts.emplace_back(noise(rng), u(rng), 0.5f * u(rng));        // wall
  for (int k = 0; k < 300; ++k) pts.emplace_back(u(rng), noise(rng) + 4.f, 0.5f * u(rng));  // wall
  for (auto& p : pts) p += Eigen::Vector3f(3.f, -2.f, -1.5f);
  registration::FastFeatureParams p;
  p.keypoint_voxel = 1.0;
  const registration::FastFeatures f = computeFastFeatures(pts, p);
  std::vector<Eigen::Vector3f> nrm(pts.size(), Eigen::Vector3f::Zero());
  std::vector<char> valid(pts.size(), 0);
  for (std::size_t c = 0; c < f.kept.size(); ++c) {
    nrm[static_cast<std::size_t>(f.kept[c])] = f.normals[c];
    valid[static_cast<std::size_t>(f.kept[c])] = 1;
  }
  ASSERT_GT(f.keypoints.size(), 20u);
  double worst = 0.0, total = 0.0;
  for (std::size_t c = 0; c < f.keypoints.size(); ++c) {
    const auto i = static_cast<std::size_t>(f.kept[static_cast<std::size_t>(f.keypoints[c])]);
    const Eigen::VectorXf ref =
        referenceFpfh(pts, nrm, valid, i, static_cast<float>(p.spfh_radius), static_cast<float>(p.fpfh_radius));
    const double diff = (ref - f.features.col(static_cast<Eigen::Index>(c))).cwiseAbs().sum();  // of 300
    worst = std::max(worst, diff);
    total += diff;
  }
  std::printf("FPFH vs definition: mean L1 %.4f, worst %.4f (of 300)\n", total / f.keypoints.size(), worst);
  // Only angles within rounding of a bin edge may land in the neighbouring bin.
  EXPECT_LT(total / static_cast<double>(f.keypoints.size()), 0.5);
  EXPECT_LT(worst, 3.0);
}
