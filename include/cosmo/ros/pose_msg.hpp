#pragma once
// geometry_msgs <-> cosmo::Pose3 and ROS time <-> StampNs, shared by the nodes. Poses go out through tf2_eigen;
// incoming quaternions are normalised (a real robot's odometry is not always unit-norm).
#include <geometry_msgs/Pose.h>
#include <ros/time.h>
#include <tf2_eigen/tf2_eigen.h>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::ros_glue {

inline geometry_msgs::Pose poseToMsg(const Pose3& T) { return tf2::toMsg(T); }

inline Pose3 poseFromMsg(const geometry_msgs::Pose& p) {
  return makePose(Eigen::Vector3d(p.position.x, p.position.y, p.position.z),
                  Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z));
}

inline ros::Time stampToRos(StampNs t) {
  ros::Time r;
  r.fromNSec(t);
  return r;
}

}  // namespace cosmo::ros_glue
