// The nodes' markers (ros/markers.hpp) and the recorder messages a front-end sends (ros/frontend_msgs.hpp): rviz
// gets no empty or one-point line, closures carry their label's colour, poses travel bit-exact.
#include <gtest/gtest.h>

#include "../support/keyframe_records.hpp"
#include "cosmo/ros/frontend_msgs.hpp"
#include "cosmo/ros/markers.hpp"
#include "cosmo/ros/pose_msg.hpp"

using namespace cosmo;

namespace {
Pose3 at(double x, double y) { return test::planarPose(x, y); }
/// A keyframe whose odometry is its reference.
frontend::KeyframeRecord keyframe(std::size_t index, const Pose3& pose) {
  return test::keyframeRecord(index, pose, pose);
}
}  // namespace

TEST(Markers, ALineIsDeletedUntilItHasContent) {
  frontend::FrontendMap map('a');
  map.addKeyframe(keyframe(0, at(0, 0)));
  const visualization_msgs::MarkerArray one = ros_glue::frontendMarkers(map, 'a', "world", ros::Time(1.0));
  ASSERT_EQ(one.markers.size(), 3u);
  EXPECT_EQ(one.markers[0].ns, "a/trajectory");
  EXPECT_EQ(one.markers[0].action, visualization_msgs::Marker::DELETE);
  EXPECT_EQ(one.markers[1].points.size(), 1u);  // the keyframe sphere
  EXPECT_EQ(one.markers[2].action, visualization_msgs::Marker::DELETE);
  map.addKeyframe(keyframe(1, at(2, 0)));
  EXPECT_EQ(ros_glue::frontendMarkers(map, 'a', "world", ros::Time(1.0)).markers[0].points.size(), 2u);
}

TEST(Markers, ClosuresAreLiftedAndColouredByTheirLabel) {
  frontend::FrontendMap map('a');
  map.addKeyframe(keyframe(0, at(0, 0)));
  map.addKeyframe(keyframe(1, at(2, 0)));
  frontend::LoopClosureAttempt a;
  a.owner = a.robot1 = a.robot2 = 'a';
  a.index1 = 0;
  a.index2 = 1;
  a.accepted = false;
  map.addClosure(a);
  const visualization_msgs::Marker lcs = ros_glue::frontendMarkers(map, 'a', "world", ros::Time(1.0)).markers[2];
  ASSERT_EQ(lcs.points.size(), 2u);
  EXPECT_GT(lcs.points[0].z, 1.0);
  EXPECT_EQ(lcs.colors[0], ros_glue::closureLabelColor(frontend::ClosureLabel::Rejected));
}

TEST(Markers, NoLinksIsADelete) {
  comm::RadioSimulator radio(comm::RadioParams::wifi(), {'a', 'b'}, 1);
  const auto array = ros_glue::linkMarkers(radio, {}, 0.0, "world", ros::Time(1.0));
  ASSERT_EQ(array.markers.size(), 1u);
  EXPECT_EQ(array.markers[0].action, visualization_msgs::Marker::DELETE);
}

TEST(FrontendMsgs, KeyframePosesTravelBitExact) {
  frontend::KeyframeRecord kf = keyframe(3, at(1.0 / 3.0, 2.0 / 7.0));
  kf.relative = makePose(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Quaterniond(0.9, 0.1, 0.2, 0.3).normalized());
  const cosmo::RecorderKeyframe m = ros_glue::recorderKeyframeMsg(kf, "world");
  EXPECT_EQ(m.robot, "a");
  EXPECT_EQ(m.index, 3u);
  EXPECT_TRUE(m.has_reference);
  EXPECT_TRUE(ros_glue::poseFromExactOrMsg(m.odometry_from_previous_exact, m.odometry_from_previous).matrix() ==
              kf.relative.matrix());
  EXPECT_TRUE(ros_glue::poseFromExactOrMsg(m.reference_exact, m.reference).matrix() == kf.reference->matrix());
}
