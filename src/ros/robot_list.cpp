#include "cosmo/ros/robot_list.hpp"

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

}  // namespace cosmo::ros_glue
