// poseGraph(), ownerPoses() and trajectoryError() on the tiny example of jrl.md §12.
#include <gtest/gtest.h>

#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/pose_graph.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/trajectory_error.hpp"

using namespace cosmo;
using namespace cosmo::jrl;

namespace {
const std::string kTiny = std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl";
}

TEST(JrlPoseGraph, TinyExampleKindsLabelsAndOwnerValues) {
  const Dataset d = readJrl(kTiny);
  const PoseGraph g = poseGraph(d);
  ASSERT_EQ(g.factors.size(), 7u);
  std::map<FactorKind, int> kinds;
  for (const auto& f : g.factors) ++kinds[f.kind];
  EXPECT_EQ(kinds[FactorKind::Prior], 2);
  EXPECT_EQ(kinds[FactorKind::Odometry], 3);
  EXPECT_EQ(kinds[FactorKind::LoopClosure], 1);
  EXPECT_EQ(kinds[FactorKind::InterRobotLoopClosure], 1);
  const PoseFactor& outlier = g.factors[3];  // a, entry 2, measurement 1
  EXPECT_EQ(outlier.robot, 'a');
  EXPECT_EQ(outlier.id, (FactorId{2, 1}));
  EXPECT_TRUE(outlier.outlier && outlier.potential_outlier);
  EXPECT_EQ(outlier.stamp, 1700000001000000000ull);
  EXPECT_TRUE(g.factors[6].potential_outlier);
  EXPECT_FALSE(g.factors[6].outlier);
  EXPECT_NEAR(g.factors[6].covariance(2, 3), 0.0005, 1e-15);
  // a1: the owner's initialization (2.25, 0, 0), not b's copy (2.0, 0.25, 0).
  EXPECT_NEAR((g.initialization.at(symbol('a', 1)).translation() - Eigen::Vector3d(2.25, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(g.initialization.size(), 5u);
  EXPECT_EQ(g.ownKeys('a'), (std::vector<Key>{symbol('a', 0), symbol('a', 1), symbol('a', 2)}));
  EXPECT_EQ(g.stamps.at(symbol('b', 1)), 1700000000750000000ull);
}

TEST(JrlTrajectoryError, OwnPosesOnlyNoAlignment) {
  const PoseGraph g = poseGraph(readJrl(kTiny));
  const TrajectoryError zero = trajectoryError(g.robots, g.groundtruth, g.groundtruth);
  EXPECT_EQ(zero.overall.trans_m, 0.0);
  EXPECT_EQ(zero.overall.poses, 5u);
  // Initialization errors: a 0, 0.25, 0.25*sqrt2; b 0, 0.25.
  const TrajectoryError e = trajectoryError(g.robots, g.initialization, g.groundtruth);
  EXPECT_NEAR(e.robots.at('a').trans_m, std::sqrt((0.0625 + 0.125) / 3.0), 1e-12);
  EXPECT_NEAR(e.robots.at('b').trans_m, std::sqrt(0.0625 / 2.0), 1e-12);
  EXPECT_NEAR(e.overall.trans_m, std::sqrt((0.0625 + 0.125 + 0.0625) / 5.0), 1e-12);
  EXPECT_EQ(e.overall.rot_rad, 0.0);
  PoseMap missing = g.initialization;
  missing.erase(symbol('b', 1));
  EXPECT_THROW(trajectoryError(g.robots, missing, g.groundtruth), std::runtime_error);
}
