#pragma once
// Seeing a peer node the way `rosnode ping` does (live::PeerWatch holds the policy):
// - probePeer(): the master's lookupNode, then a TCP connection to the node's XML-RPC URI and its getPid, each
//   bounded by a timeout, so that a peer behind a dead route or a stopped process cannot block the caller;
// - PeerMonitor: a thread that probes the expected peers about once a second, feeds a PeerWatch, logs what its
//   policy says (prefixed with the owner's name) and keeps the reason to stop the run when there is one.
// A node's XML-RPC server runs on roscpp's own thread, so a node busy in a long computation still answers; a
// SIGKILLed node's port refuses at once, while the master still lists it until it is replaced or cleaned up.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "cosmo/live/peer_address_hint.hpp"
#include "cosmo/live/peer_watch.hpp"

namespace cosmo::ros_glue {

/// Thrown by a wait when the peer policy stops the run; what() is the reason (it names the peer).
class RunStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One probe of the node named `node` (a resolved name, e.g. "/b/frontend"), `timeout` s at most per step.
live::PeerProbe probePeer(const std::string& node, double timeout = 1.0);

/// What this machine finds out about the address a probed peer registered, for the hints of
/// live/peer_address_hint.hpp (the probe's host resolution and connection, and whether it is a loopback one).
live::PeerAddress peerAddress(const live::PeerProbe& probe);

/// Why this node's topic connections with the peer at `peer_uri` (alive) are not made: its topic server for
/// `topic` (one it publishes; XML-RPC requestTopic) does not accept a connection from here, or it does, and then the
/// peer cannot reach this node. Each step bounded by `timeout` s.
std::string unlinkedReason(const std::string& peer_uri, const std::string& topic, double timeout = 1.0);

/// The wall time in seconds (the clock PeerMonitor passes to its watch).
double wallSeconds();

class PeerMonitor {
 public:
  /// `owner`: the node that watches, for its messages (e.g. "player").
  PeerMonitor(std::string owner, live::PeerWatch watch, double period = 1.0);
  ~PeerMonitor();
  PeerMonitor(const PeerMonitor&) = delete;
  PeerMonitor& operator=(const PeerMonitor&) = delete;

  /// The owner's own topic check of `node` (called on the monitor's thread before each review); set before start().
  /// `topic`: one the peer publishes and the owner subscribes to, to tell why the link is missing (unlinkedReason).
  void setLinkCheck(const std::string& node, std::function<bool()> linked, const std::string& topic = "");
  /// Called once, on the monitor's thread, when the policy says the run must stop (instead of the monitor's own
  /// error message); set before start().
  void onStop(std::function<void(const std::string&)> callback) { on_stop_ = std::move(callback); }
  /// Starts the watch (its connect timeouts count from now) and the probing thread.
  void start();
  /// Probes every peer and reviews the policy once, on the calling thread (start() runs it periodically).
  void probeOnce();

  std::optional<std::string> stopReason() const;
  bool connected() const;
  bool alive(const std::string& node) const;
  live::PeerState state(const std::string& node) const;
  std::string describe(const std::string& node) const;

 private:
  void loop();

  std::string owner_;
  double period_;
  mutable std::mutex mutex_;
  live::PeerWatch watch_;
  std::map<std::string, std::function<bool()>> link_checks_;
  std::map<std::string, std::string> link_topics_;
  std::map<std::string, double> link_hint_at_;  ///< since when a link is missing / its reason was last looked for
  std::function<void(const std::string&)> on_stop_;
  bool stop_reported_ = false;
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  std::atomic<bool> quit_{false};
  std::thread thread_;
};

}  // namespace cosmo::ros_glue
