// AssociationMemory: a remembered association is only reused while it is the one a new k-NN search and fit
// would give, so the constraints equal those of a fresh associateFeatures at the moved pose.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cosmo/odometry/feature_correspondences.hpp"
#include "cosmo/odometry/local_feature_map.hpp"

using namespace cosmo;

namespace {
struct Scene {
  std::vector<Eigen::Vector3d> map_edges, map_planes, edges, planes;
};

/// Map: a ground plane, two walls and vertical poles (edges), sampled with noise; features: points of the
/// same surfaces (sensor frame = map frame at identity).
Scene makeScene(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-15.0, 15.0), n(-0.01, 0.01), h(0.0, 3.0);
  Scene s;
  for (int i = 0; i < 4000; ++i) s.map_planes.push_back({u(rng), u(rng), -1.5 + n(rng)});
  for (int i = 0; i < 1500; ++i) s.map_planes.push_back({u(rng), 6.0 + n(rng), -1.5 + h(rng)});
  for (int i = 0; i < 1500; ++i) s.map_planes.push_back({-8.0 + n(rng), u(rng), -1.5 + h(rng)});
  for (int p = 0; p < 20; ++p) {
    const double x = u(rng), y = u(rng);
    for (int i = 0; i < 30; ++i) s.map_edges.push_back({x + n(rng), y + n(rng), -1.5 + h(rng)});
  }
  for (int i = 0; i < 600; ++i) s.planes.push_back({u(rng), u(rng), -1.5 + n(rng)});
  for (int i = 0; i < 200; ++i) s.planes.push_back({u(rng), 6.0 + n(rng), -1.5 + h(rng)});
  for (int i = 0; i < 200; ++i)
    s.edges.push_back(s.map_edges[static_cast<std::size_t>(i) * 3] + Eigen::Vector3d(n(rng), n(rng), 0.0));
  return s;
}

void expectSameConstraints(const std::vector<odometry::FeatureConstraint>& a,
                           const std::vector<odometry::FeatureConstraint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].edge, b[i].edge);
    ASSERT_EQ(a[i].feature, b[i].feature);
    // Same line / plane (the normal's sign may differ with the summation order of the fit).
    const double sign = a[i].normal.dot(b[i].normal) < 0.0 ? -1.0 : 1.0;
    EXPECT_NEAR((a[i].normal - sign * b[i].normal).norm(), 0.0, 1e-9) << i;
    EXPECT_NEAR(a[i].offset, sign * b[i].offset, 1e-9) << i;
  }
}
}  // namespace

TEST(AssociationMemory, ReusedConstraintsEqualAFreshAssociation) {
  const Scene s = makeScene(5);
  odometry::LoamParams params;
  odometry::LocalFeatureMap map;
  map.add(s.map_edges, s.map_planes);
  odometry::AssociationMemory memory;
  memory.reset(s.edges.size(), s.planes.size());
  std::vector<odometry::FeatureConstraint> remembered, fresh;
  const Pose3 T0 = makePose(0.2, -0.1, 0.02, 0.0, 0.0, 0.01);
  associateFeaturesRemembering(s.edges, s.planes, map, T0, params, remembered, memory, 1, true);
  associateFeatures(s.edges, s.planes, map, T0, params, fresh);
  expectSameConstraints(remembered, fresh);
  EXPECT_EQ(memory.reused, 0u);
  EXPECT_GT(remembered.size(), 500u);
  // Small and larger moves: reused where provably unchanged, searched elsewhere; always the fresh result.
  for (double step : {0.0005, 0.003, 0.02, 0.2}) {
    const Pose3 T = T0 * makePose(step, -step, 0.5 * step, 0.0, 0.0, 0.1 * step);
    const std::size_t reused_before = memory.reused;
    associateFeaturesRemembering(s.edges, s.planes, map, T, params, remembered, memory, 1, true);
    associateFeatures(s.edges, s.planes, map, T, params, fresh);
    expectSameConstraints(remembered, fresh);
    if (step <= 0.003) { EXPECT_GT(memory.reused - reused_before, s.edges.size() / 2) << step; }
  }
}

TEST(AssociationMemory, SubsampledListsUseTheFullIndex) {
  const Scene s = makeScene(9);
  odometry::LoamParams params;
  odometry::LocalFeatureMap map;
  map.add(s.map_edges, s.map_planes);
  odometry::AssociationMemory memory;
  memory.reset(s.edges.size(), s.planes.size());
  std::vector<Eigen::Vector3d> sub_edges, sub_planes;
  for (std::size_t i = 0; i < s.edges.size(); i += 4) sub_edges.push_back(s.edges[i]);
  for (std::size_t i = 0; i < s.planes.size(); i += 4) sub_planes.push_back(s.planes[i]);
  std::vector<odometry::FeatureConstraint> cs, fresh;
  const Pose3 T = makePose(0.1, 0.0, 0.0, 0.0, 0.0, 0.0);
  associateFeaturesRemembering(sub_edges, sub_planes, map, T, params, cs, memory, 4, true);
  const std::size_t searched_sub = memory.searched;
  // All features at (almost) the same pose, reading only: the subsample is answered from memory.
  const Pose3 T2 = T * makePose(1e-4, 0.0, 0.0, 0.0, 0.0, 0.0);
  associateFeaturesRemembering(s.edges, s.planes, map, T2, params, cs, memory, 1, false);
  associateFeatures(s.edges, s.planes, map, T2, params, fresh);
  expectSameConstraints(cs, fresh);
  EXPECT_GE(memory.reused, searched_sub * 9 / 10);
  EXPECT_EQ(memory.reused + memory.searched, searched_sub + s.edges.size() + s.planes.size());
}

TEST(LocalFeatureMapWindow, SlidingMapAnswersLikeAFreshOne) {
  // Four scans through a 3-scan window (the trees are rebuilt in the previous tree's order) against a map
  // built from the last three scans only.
  std::vector<Scene> scans;
  for (std::uint64_t seed : {21, 22, 23, 24}) scans.push_back(makeScene(seed));
  odometry::LocalFeatureMap sliding(3), fresh(3);
  for (const Scene& s : scans) sliding.add(s.map_edges, s.map_planes);
  for (std::size_t i = 1; i < scans.size(); ++i) fresh.add(scans[i].map_edges, scans[i].map_planes);
  EXPECT_EQ(sliding.numPlanePoints(), fresh.numPlanePoints());
  EXPECT_EQ(sliding.numEdgePoints(), fresh.numEdgePoints());
  std::vector<Eigen::Vector3d> a, b;
  for (const Eigen::Vector3d& q : scans[0].planes) {
    sliding.nearestPlanes(q, 5, 4.0, a);
    fresh.nearestPlanes(q, 5, 4.0, b);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ((a[i] - q).squaredNorm(), (b[i] - q).squaredNorm());
  }
  for (const Eigen::Vector3d& q : scans[0].edges) {
    sliding.nearestEdges(q, 5, 2.0, a);
    fresh.nearestEdges(q, 5, 2.0, b);
    ASSERT_EQ(a, b);
  }
}
