#include "cosmo/ros/robot_list.hpp"

#include <ros/console.h>
#include <ros/param.h>
#include <ros/this_node.h>

#include <sstream>
#include <stdexcept>

namespace cosmo::ros_glue {

namespace {
std::vector<std::string> splitIds(std::string s) {
  for (char& c : s)
    if (c == ',' || c == '[' || c == ']' || c == '\'' || c == '"') c = ' ';
  std::istringstream in(s);
  std::vector<std::string> names;
  for (std::string n; in >> n;) names.push_back(n);
  return names;
}
}  // namespace

std::vector<char> readRobotsParam(const ros::NodeHandle& pnh, const std::string& fallback) {
  std::vector<std::string> names;
  XmlRpc::XmlRpcValue v;
  if (pnh.getParam("robots", v)) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      for (int i = 0; i < v.size(); ++i) {
        if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString)
          throw std::runtime_error("~robots: entry " + std::to_string(i) + " is not a string");
        names.push_back(static_cast<std::string>(v[i]));
      }
    } else if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
      names = splitIds(static_cast<std::string>(v));
    } else {
      throw std::runtime_error("~robots: expected a list of robot ids, e.g. [a, b, c]");
    }
  } else {
    names = splitIds(fallback);
  }
  if (names.empty()) throw std::runtime_error("~robots: no robots given (e.g. _robots:='[a, b, c]')");
  std::vector<char> ids;
  for (const auto& n : names) {
    if (n.size() != 1) throw std::runtime_error("~robots: robot id '" + n + "' must be a single character");
    ids.push_back(n[0]);
  }
  return ids;
}

void publishTeamRobots(const std::vector<char>& robots) {
  std::vector<std::string> ids;
  for (char r : robots) ids.emplace_back(1, r);
  ros::param::set(kTeamRobotsParam, ids);
}

std::vector<char> readTeamRobots(const ros::NodeHandle& pnh) {
  if (pnh.hasParam("robots")) return readRobotsParam(pnh);
  ROS_INFO("%s: robots from the player's sequence (%s)", ros::this_node::getName().c_str(), kTeamRobotsParam);
  while (ros::ok()) {
    if (ros::param::has(kTeamRobotsParam)) return readRobotsParam(ros::NodeHandle("/player"));
    ros::WallDuration(0.1).sleep();
  }
  throw std::runtime_error(std::string("shut down before the player set ") + kTeamRobotsParam);
}

char nodeRobot(const ros::NodeHandle& pnh) {
  std::string ns = ros::this_node::getNamespace(), robot;
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  pnh.param<std::string>("robot", robot, ns);
  if (robot.size() != 1 || robot[0] < 'a' || robot[0] > 'z')
    throw std::runtime_error("~robot must be one lower-case letter (or run in namespace /<r>), got '" + robot + "'");
  return robot[0];
}

}  // namespace cosmo::ros_glue
