#include "cosmo/odometry/keyframer.hpp"

namespace cosmo::odometry {

Keyframer::Keyframer(double distance) : distance_(distance) {}

KeyframeDecision Keyframer::update(const Pose3& odom_pose) {
  KeyframeDecision d;
  if (count_ == 0) {
    d.is_keyframe = true;
    d.index = 0;
    count_ = 1;
    last_kf_ = last_pose_ = odom_pose;
    travelled_ = 0.0;
    return d;
  }
  travelled_ += (last_pose_.inverse() * odom_pose).translation().norm();
  last_pose_ = odom_pose;
  if (travelled_ > distance_) {
    d.is_keyframe = true;
    d.index = count_++;
    d.relative = orthonormalized(last_kf_.inverse() * odom_pose);
    last_kf_ = odom_pose;
    travelled_ = 0.0;
  }
  return d;
}

}  // namespace cosmo::odometry
