#pragma once
// Test helpers: planar poses and the KeyframeRecord a front-end reports, filled as the map and marker tests need
// them (robot 'a' unless told).
#include <cstddef>
#include <optional>

#include "cosmo/common/pose.hpp"
#include "cosmo/frontend/robot_frontend.hpp"

namespace cosmo::test {

/// The pose at (x, y, 0) with heading `yaw` (rad).
inline Pose3 planarPose(double x, double y, double yaw = 0.0) {
  return makePose(Eigen::Vector3d(x, y, 0), Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())));
}

/// Keyframe `index` of `robot` at odometry pose `odom`, with its reference pose when it has one.
inline frontend::KeyframeRecord keyframeRecord(std::size_t index, const Pose3& odom, std::optional<Pose3> reference,
                                               char robot = 'a') {
  frontend::KeyframeRecord kf;
  kf.robot = robot;
  kf.index = index;
  kf.odom_pose = odom;
  kf.reference = reference;
  return kf;
}

}  // namespace cosmo::test
