// Hash-grid neighbour pairs against brute force (same pair set, each pair once, same squared distances), on
// a seeded random cloud with negative coordinates, cell-boundary points and duplicates; and the fast features
// built on them are deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

#include "cosmo/registration/fast_features.hpp"
#include "cosmo/registration/neighbour_pairs.hpp"

using namespace cosmo;

namespace {
std::vector<Eigen::Vector3f> randomCloud(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-6.f, 6.f);
  std::vector<Eigen::Vector3f> pts;
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), 0.5f * u(rng));
  pts.emplace_back(1.5f, 0.f, 0.f);   // exactly on cell boundaries (radius 1.5)
  pts.emplace_back(0.f, 0.f, 0.f);
  pts.emplace_back(-1.5f, 0.f, 0.f);
  pts.push_back(pts[3]);              // a duplicate point
  return pts;
}
}  // namespace

TEST(NeighbourPairs, MatchesBruteForce) {
  const auto pts = randomCloud(1500, 7);
  for (const float radius : {0.9f, 1.5f}) {
    const NeighbourPairs pairs = findNeighbourPairs(pts, radius);
    std::set<std::pair<std::uint32_t, std::uint32_t>> got;
    for (std::size_t e = 0; e < pairs.size(); ++e) {
      const std::uint32_t i = pairs.first[e], j = pairs.second[e];
      ASSERT_NE(i, j);
      EXPECT_TRUE(got.insert({std::min(i, j), std::max(i, j)}).second) << "pair listed twice";
      EXPECT_NEAR(pairs.squared_distance[e], (pts[i] - pts[j]).squaredNorm(), 1e-5f);
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

TEST(NeighbourPairs, EmptyAndSingle) {
  EXPECT_EQ(findNeighbourPairs({}, 1.f).size(), 0u);
  EXPECT_EQ(findNeighbourPairs({Eigen::Vector3f(1, 2, 3)}, 1.f).size(), 0u);
}

TEST(FastFeatures, Deterministic) {
  const auto pts = randomCloud(3000, 11);
  FastFeatureParams p;
  p.keypoint_voxel = 0.9;
  const FastFeatures a = computeFastFeatures(pts, p), b = computeFastFeatures(pts, p);
  ASSERT_EQ(a.kept, b.kept);
  ASSERT_EQ(a.keypoints, b.keypoints);
  ASSERT_GT(a.keypoints.size(), 10u);
  EXPECT_TRUE((a.features.array() == b.features.array()).all());
  // Each of the three sub-histograms sums to 100.
  for (Eigen::Index c = 0; c < a.features.cols(); ++c)
    for (int s = 0; s < 3; ++s) EXPECT_NEAR(a.features.col(c).segment<11>(s * 11).sum(), 100.f, 1e-2f);
}
