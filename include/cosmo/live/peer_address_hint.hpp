#pragma once
// Why a peer node cannot be reached, in the terms a user of a team spread over several machines can act on
// (README "A robot per machine"). ROS 1 has each node register its own XML-RPC URI, built from ROS_IP /
// ROS_HOSTNAME / the host name of its machine, and every other node connects to that address: a node that reaches
// the master is not necessarily reachable back. The peer watch (peer_watch.hpp) sees the symptoms; these say what
// they most likely mean. ROS-free: the ROS glue resolves the address and tries the connection.
#include <string>

namespace cosmo::live {

/// What the watcher found out about the address a peer registered.
struct PeerAddress {
  std::string uri;         ///< the URI the peer registered (XML-RPC, or its topic server's host:port)
  std::string host;        ///< the host part of it
  bool resolved = true;    ///< the host name resolves here
  bool loopback = false;   ///< it is, or resolves to, a loopback address (127.x, ::1)
  bool refused = false;    ///< a connection was refused (nothing listens there)
  bool timed_out = false;  ///< a connection got no answer in time
};

/// The peer registered with the master but its XML-RPC server does not answer at `peer.uri`.
std::string unreachableHint(const PeerAddress& peer);

/// The peer's XML-RPC server answers, but its topic server (TCPROS, `topic_server`) cannot be connected to.
std::string unlinkedHint(const PeerAddress& topic_server);

/// The peer never registered with the master at `master_uri`.
std::string neverRegisteredHint(const std::string& master_uri);

}  // namespace cosmo::live
