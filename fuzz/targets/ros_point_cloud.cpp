// The ROS message glue: bytes deserialized by roscpp into a sensor_msgs::PointCloud2 (as a subscriber receives
// it), then ros_glue::fromPointCloud2 (src/ros/point_cloud.cpp). roscpp's deserializer (not instrumented) sizes
// a vector from its length field before it checks the bytes are there (a 4 GB allocation for a 4-byte length):
// only messages whose lengths fit the input (trials::parseRos1PointCloud2's check) are handed to it: what roscpp
// does with the others is roscpp's, before any cosmo code runs.
#include <ros/serialization.h>
#include <sensor_msgs/PointCloud2.h>

#include "../fuzz_target.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(ros_point_cloud) {
  trials::parseRos1PointCloud2(data, size, "input");
  sensor_msgs::PointCloud2 msg;
  try {
    ros::serialization::IStream in(const_cast<std::uint8_t*>(data), static_cast<std::uint32_t>(size));
    ros::serialization::deserialize(in, msg);
  } catch (const ros::serialization::StreamOverrunException&) {
    return;  // roscpp refuses it: the subscriber never sees it
  }
  ros_glue::fromPointCloud2(msg, true, "input");
  ros_glue::fromPointCloud2(msg, false, "input");
}
