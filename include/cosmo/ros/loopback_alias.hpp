#pragma once
// A node given a loopback alias as its address (ROS_IP=127.0.0.2, to try a team on one machine as if each robot
// had its own) must be reachable there. roscpp 1.15 is not: when ROS_IP starts with "127." (or ROS_HOSTNAME is
// "localhost") its Transport sets only_localhost_allowed_ (ros_comm clients/roscpp/src/libros/transport/
// transport.cpp, Transport::Transport) and TransportTCP::listen then binds the topic server (TCPROS) to
// INADDR_LOOPBACK = 127.0.0.1 (transport_tcp.cpp), while the node registers itself under the ROS_IP address:
// its XML-RPC server (bound to every address by xmlrpcpp) answers at 127.0.0.2, its topic connections to
// 127.0.0.2:<port> are refused, and no subscriber ever connects (rospy binds to the 127.x address itself). The
// same node with ROS_HOSTNAME=127.0.0.2 and no ROS_IP registers the same address and binds to every address.
#include <optional>
#include <string>

namespace cosmo::ros_glue {

struct RosAddressEnv {
  std::optional<std::string> ros_ip, ros_hostname;
};

/// The address roscpp registers (ROS_HOSTNAME, else ROS_IP) when it serves its topics on 127.0.0.1 only and that
/// address is another one (so its topics cannot be reached); nullopt when the environment is fine.
std::optional<std::string> unreachableTopicAddress(const RosAddressEnv& env);

/// Before ros::init: when this process's environment is such a case, it serves its topics as ROS_HOSTNAME=<that
/// address> without ROS_IP does. Returns what it did, for the log ("" when nothing).
std::string serveTopicsWhereRegistered();

}  // namespace cosmo::ros_glue
