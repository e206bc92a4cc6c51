#include "cosmo/ros/node_main.hpp"

#include <ros/ros.h>

#include <exception>

namespace cosmo::ros_glue {

int runNode(const char* name, const std::function<void()>& body) {
  try {
    body();
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 1;
  }
  return 0;
}

bool waitUntil(const std::function<bool()>& done, const ros::WallTime& deadline, double period) {
  while (ros::ok()) {
    if (done()) return true;
    if (ros::WallTime::now() >= deadline) return false;
    ros::WallDuration(period).sleep();
  }
  return false;
}

ros::WallTime wallDeadline(double seconds) { return ros::WallTime::now() + ros::WallDuration(seconds); }

}  // namespace cosmo::ros_glue
