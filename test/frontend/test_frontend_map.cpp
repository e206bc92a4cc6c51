// What a front-end's map display shows (frontend/frontend_map.hpp): keyframes in the world frame by their reference
// or the aligned odometry, loop closures between known keyframes with their labels.
#include <gtest/gtest.h>

#include "../support/keyframe_records.hpp"
#include "cosmo/frontend/frontend_map.hpp"

using namespace cosmo;
using namespace cosmo::frontend;

namespace {
using test::keyframeRecord;
Pose3 at(double x, double y, double yaw = 0.0) { return test::planarPose(x, y, yaw); }
LoopClosureAttempt closure(char r1, std::size_t i1, char r2, std::size_t i2, const Pose3& m, bool accepted = true) {
  LoopClosureAttempt a;
  a.owner = a.robot1 = r1;
  a.index1 = i1;
  a.robot2 = r2;
  a.index2 = i2;
  a.measurement = m;
  a.accepted = accepted;
  return a;
}
}  // namespace

TEST(FrontendMap, KeyframesWithoutReferenceAreAlignedByTheFirstKeyframesReference) {
  FrontendMap map('a');
  map.addKeyframe(keyframeRecord(0, at(1, 0), at(11, 5)));
  map.addKeyframe(keyframeRecord(1, at(3, 0), std::nullopt));
  ASSERT_EQ(map.trajectory().size(), 2u);
  EXPECT_TRUE(map.trajectory()[0].isApprox(Eigen::Vector3d(11, 5, 0)));
  EXPECT_TRUE(map.trajectory()[1].isApprox(Eigen::Vector3d(13, 5, 0)));
  EXPECT_TRUE(map.worldFromOdometry().translation().isApprox(Eigen::Vector3d(10, 5, 0)));
}

TEST(FrontendMap, ClosuresJoinKnownKeyframesAndCarryTheirLabels) {
  FrontendMap map('a', dataset::NoiseModels{});
  map.addKeyframe(keyframeRecord(0, at(0, 0), at(0, 0)));
  map.addKeyframe(keyframeRecord(1, at(2, 0), at(2, 0)));
  map.addTeammateKeyframe('b', 4, at(2, 1));
  map.addClosure(closure('a', 1, 'b', 4, at(0, 1)));         // the truth: inlier
  map.addClosure(closure('a', 0, 'b', 4, at(9, 9, 1.0)));    // far off: outlier
  map.addClosure(closure('a', 0, 'a', 1, at(2, 0), false));  // rejected
  map.addClosure(closure('a', 0, 'c', 2, at(0, 0)));         // c2 unknown: not shown
  const std::vector<ClosureSegment> shown = map.closures();
  ASSERT_EQ(shown.size(), 3u);
  EXPECT_EQ(shown[0].label, ClosureLabel::Inlier);
  EXPECT_TRUE(shown[0].from.isApprox(Eigen::Vector3d(2, 0, 0)));
  EXPECT_TRUE(shown[0].to.isApprox(Eigen::Vector3d(2, 1, 0)));
  EXPECT_EQ(shown[1].label, ClosureLabel::Outlier);
  EXPECT_EQ(shown[2].label, ClosureLabel::Rejected);
}

TEST(FrontendMap, AcceptedClosuresAreUnlabelledWithoutNoiseModels) {
  FrontendMap map('a');
  map.addKeyframe(keyframeRecord(0, at(0, 0), at(0, 0)));
  map.addKeyframe(keyframeRecord(1, at(2, 0), at(2, 0)));
  map.addClosure(closure('a', 0, 'a', 1, at(2, 0)));
  EXPECT_FALSE(map.hasNoiseModels());
  ASSERT_EQ(map.closures().size(), 1u);
  EXPECT_EQ(map.closures()[0].label, ClosureLabel::Unlabelled);
}
