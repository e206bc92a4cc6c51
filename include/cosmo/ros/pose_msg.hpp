#pragma once
// geometry_msgs <-> cosmo::Pose3 (poses and TF transforms) and ROS time <-> StampNs, shared by the nodes. Poses go
// out through tf2_eigen; incoming quaternions are normalised (a real robot's odometry is not always unit-norm).
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <tf2_eigen/tf2_eigen.h>

#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::ros_glue {

inline geometry_msgs::Pose poseToMsg(const Pose3& T) { return tf2::toMsg(T); }

inline Pose3 poseFromMsg(const geometry_msgs::Pose& p) {
  return makePose(Eigen::Vector3d(p.position.x, p.position.y, p.position.z),
                  Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z));
}

/// Bit-exact pose as 12 numbers (rotation row-major, then translation) for the messages' `*_exact` fields: the
/// quaternion of geometry_msgs/Pose does not give the same matrix back to the last bit.
inline std::vector<double> poseToExact(const Pose3& T) {
  std::vector<double> v;
  v.reserve(12);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v.push_back(T.linear()(r, c));
  for (int r = 0; r < 3; ++r) v.push_back(T.translation()(r));
  return v;
}

/// The exact pose when `exact` holds 12 numbers, else the message pose.
inline Pose3 poseFromExactOrMsg(const std::vector<double>& exact, const geometry_msgs::Pose& p) {
  if (exact.size() != 12) return poseFromMsg(p);
  Pose3 T = Pose3::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = exact[static_cast<std::size_t>(3 * r + c)];
  for (int r = 0; r < 3; ++r) T.translation()(r) = exact[static_cast<std::size_t>(9 + r)];
  return T;
}

inline ros::Time stampToRos(StampNs t) {
  ros::Time r;
  r.fromNSec(t);
  return r;
}

/// The TF transform `parent` -> `child` that places `child` at `T` in `parent`.
inline geometry_msgs::TransformStamped transformMsg(const Pose3& T, const ros::Time& stamp, const std::string& parent,
                                                    const std::string& child) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  const geometry_msgs::Pose p = poseToMsg(T);
  t.transform.translation.x = p.position.x;
  t.transform.translation.y = p.position.y;
  t.transform.translation.z = p.position.z;
  t.transform.rotation = p.orientation;
  return t;
}

}  // namespace cosmo::ros_glue
