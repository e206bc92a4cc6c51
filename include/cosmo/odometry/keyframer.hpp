#pragma once
// Distance-based keyframe selection (spec 4.2) on any odometry source (LOAM or a robot's own odometry):
// the first pose is keyframe 0; a new keyframe when the integrated odometry since the last keyframe has moved
// more than `distance` metres (path length of the scan-rate odometry, so a robot going back and forth still
// gets keyframes). The measurement between consecutive keyframes is the composition of the scan-rate odometry
// in between, i.e. T_kf(i-1)^-1 * T_kf(i) for poses in one odometry frame.
#include <cstddef>

#include "cosmo/common/pose.hpp"

namespace cosmo::odometry {

struct KeyframeDecision {
  bool is_keyframe = false;
  std::size_t index = 0;               ///< keyframe index when is_keyframe
  Pose3 relative = Pose3::Identity();  ///< odometry from the previous keyframe (index > 0)
};

class Keyframer {
 public:
  explicit Keyframer(double distance = 2.0);
  /// Feeds the next odometry pose (any fixed odometry frame).
  KeyframeDecision update(const Pose3& odom_pose);
  std::size_t numKeyframes() const { return count_; }
  const Pose3& lastKeyframePose() const { return last_kf_; }
  double distance() const { return distance_; }
  /// Path length travelled since the last keyframe (m).
  double travelledSinceKeyframe() const { return travelled_; }

 private:
  double distance_;
  std::size_t count_ = 0;
  Pose3 last_kf_ = Pose3::Identity();
  Pose3 last_pose_ = Pose3::Identity();
  double travelled_ = 0.0;
};

}  // namespace cosmo::odometry
