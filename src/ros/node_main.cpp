#include "cosmo/ros/node_main.hpp"

#include <ros/ros.h>

#include <ros/master.h>
#include <ros/xmlrpc_manager.h>

#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <exception>

#include "cosmo/ros/loopback_alias.hpp"

namespace cosmo::ros_glue {

void initNode(int& argc, char** argv, const std::string& name, std::uint32_t options) {
  const std::string note = serveTopicsWhereRegistered();
  ros::init(argc, argv, name, options);
  if (!note.empty()) ROS_WARN("%s: %s", name.c_str(), note.c_str());
}

std::string whereThisNodeIs() {
  const char* ip = std::getenv("ROS_IP");
  const char* host = std::getenv("ROS_HOSTNAME");
  const std::string from = host ? std::string("ROS_HOSTNAME=") + host
                           : ip ? std::string("ROS_IP=") + ip
                                : "the host name: set ROS_IP to this machine's address as the base reaches it";
  return "master " + ros::master::getURI() + ", this node " + ros::XMLRPCManager::instance()->getServerURI() + " (" +
         from + "): the player must run on that master and reach this node there";
}

bool endWithParent() {
  const pid_t parent = getppid();
  prctl(PR_SET_PDEATHSIG, SIGINT);
  return getppid() == parent;  // else the parent ended before prctl
}

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
