#include "cosmo/ros/loopback_alias.hpp"

#include <cstdlib>

namespace cosmo::ros_glue {

std::optional<std::string> unreachableTopicAddress(const RosAddressEnv& env) {
  const auto loopback_only = [&] {  // roscpp 1.15, Transport::Transport
    if (env.ros_hostname && *env.ros_hostname == "localhost") return true;
    return env.ros_ip && env.ros_ip->compare(0, 4, "127.") == 0;
  };
  const std::optional<std::string>& registered = env.ros_hostname ? env.ros_hostname : env.ros_ip;
  if (!registered || !loopback_only() || *registered == "localhost" || *registered == "127.0.0.1") return std::nullopt;
  return registered;
}

std::string serveTopicsWhereRegistered() {
  RosAddressEnv env;
  if (const char* ip = std::getenv("ROS_IP")) env.ros_ip = ip;
  if (const char* host = std::getenv("ROS_HOSTNAME")) env.ros_hostname = host;
  const std::optional<std::string> address = unreachableTopicAddress(env);
  if (!address) return "";
  const std::string was = (env.ros_ip ? "ROS_IP=" + *env.ros_ip : std::string()) +
                          (env.ros_ip && env.ros_hostname ? " " : "") +
                          (env.ros_hostname ? "ROS_HOSTNAME=" + *env.ros_hostname : std::string());
  setenv("ROS_HOSTNAME", address->c_str(), 1);
  unsetenv("ROS_IP");
  return was + ": roscpp would serve this node's topics on 127.0.0.1 only while registering " + *address +
         " (no peer could connect to them); running as ROS_HOSTNAME=" + *address +
         " instead (topics served on every address; set that yourself to silence this)";
}

}  // namespace cosmo::ros_glue
