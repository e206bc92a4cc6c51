#include "cosmo/live/peer_address_hint.hpp"

namespace cosmo::live {

std::string unreachableHint(const PeerAddress& p) {
  if (!p.resolved)
    return "its host name '" + p.host + "' does not resolve on this machine: set ROS_IP on the peer's machine to "
           "its address as this machine reaches it (or make the name resolve here)";
  if (p.loopback)
    return "it registered the loopback address " + p.host + ", which reaches it from its own machine only: if it "
           "runs on another machine, set ROS_IP there to its network address";
  if (p.timed_out)
    return "nothing answers at " + p.host + " from here: ROS_IP on the peer's machine names an address this machine "
           "cannot reach, or a firewall drops the connection";
  if (p.refused)
    return "nothing listens at " + p.uri + ": the node died after registering, or ROS_IP on its machine names "
           "another machine";
  return "its XML-RPC server at " + p.uri + " does not answer";
}

std::string unlinkedHint(const PeerAddress& t) {
  const bool alias = t.host.compare(0, 4, "127.") == 0 && t.host != "127.0.0.1";
  if (alias && t.refused)
    return "its topic server at " + t.uri + " refuses connections while its XML-RPC server answers: roscpp serves "
           "topics on 127.0.0.1 only when ROS_IP is a 127.x address (use ROS_HOSTNAME=" + t.host + " instead)";
  if (t.refused || t.timed_out)
    return "its topic server at " + t.uri + (t.refused ? " refuses connections" : " does not answer") +
           " while its XML-RPC server answers: a firewall on its machine that lets only some ports through";
  return "its topic connections to " + t.uri + " are not made yet";
}

std::string neverRegisteredHint(const std::string& master_uri) {
  return "it never registered with the master " + master_uri + ": is it started, with ROS_MASTER_URI=" + master_uri +
         " on its machine, and does that machine reach this one (a robot launch with another master URI starts a "
         "master of its own)?";
}

}  // namespace cosmo::live
