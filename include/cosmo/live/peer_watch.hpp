#pragma once
// The peers of a run and what to do when one dies or never connects: one rule for every node (docs/design.md,
// "A peer that dies or never connects").
//
// A peer is a ROS node another node depends on (the player's front-ends, comm_broker and recorder; the recorder's
// player), named by its node name and seen the way `rosnode ping` sees it: registered with the master, and its own
// XML-RPC server answering getPid. A driver (ros_glue::PeerMonitor) probes each peer about once a second and feeds
// the result here with the wall time; this object holds no clock and no ROS, so the policy is tested without a
// master.
//
// States: waiting (never seen), unreachable (registered, never answered), alive (pid, uri), gone (was alive, now
// does not answer or is no longer registered), restarted (alive again with another pid or uri).
// Policy (review()), per role and mode:
//   never connects  front-end, broker: lockstep stop after connect_timeout; realtime go on without it, loudly
//                   recorder: stop after recorder_timeout (nothing would be written)
//   dies            front-end, broker: lockstep stop after death_grace; realtime wait for its respawn, naming it
//                   recorder: wait for its respawn up to recorder_timeout, then stop
//                   player (watched by the recorder): stop after death_grace
//   restarts        front-end, broker: lockstep stop (its state is lost); realtime carry on
//                   recorder: carry on (the senders resend what it did not acknowledge)
// A peer waited for is named every notice_period. "Stop" is sticky: stopReason() keeps the first reason.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cosmo::live {

enum class RunMode { Lockstep, Realtime };
enum class PeerRole { Frontend, Broker, Recorder, Player };
enum class PeerState { Waiting, Unreachable, Alive, Gone, Restarted };

const char* peerStateName(PeerState state);

/// One look at a peer: the master's answer and the node's own.
struct PeerProbe {
  bool registered = false;  ///< the master knows the node
  std::string uri;          ///< its XML-RPC URI, when registered
  bool answered = false;    ///< its XML-RPC server answered getPid
  int pid = 0;              ///< when answered
  bool refused = false;     ///< not answered: the connection was refused (nothing listens: a dead process)
  std::string error;        ///< not answered: why
  std::string hint;         ///< not answered: the likely cause across machines (peer_address_hint.hpp)
};

struct PeerPolicyParams {
  double connect_timeout = 30.0;   ///< s after start(): a front-end or broker not connected by then is given up
  double death_grace = 5.0;        ///< s a peer that was alive may not answer before it counts as dead
  double recorder_timeout = 60.0;  ///< s the recorder may be missing (it is respawned) before the run stops
  double notice_period = 5.0;      ///< s between the messages naming a peer that is waited for
};

struct PeerNotice {
  bool warning = false;
  std::string text;
};

class PeerWatch {
 public:
  explicit PeerWatch(RunMode mode, PeerPolicyParams params = {});

  /// An expected peer: its node name, role and what it is for messages (e.g. "the front-end of robot b").
  void expect(const std::string& node, PeerRole role, const std::string& what);
  /// The driver is ready to run: connect timeouts count from `now`.
  void start(double now);
  /// A probe of `node` made at `now` (an unknown node is ignored).
  void observe(const std::string& node, const PeerProbe& probe, double now);
  /// The driver's own topic connections with `node` are made (a peer counts as connected when it is alive and
  /// linked; linked by default).
  void setLinked(const std::string& node, bool linked, const std::string& hint = "");
  /// The master's URI, for the message about a peer that never registered.
  void setMaster(const std::string& uri) { master_uri_ = uri; }

  /// The policy at `now`: the messages due, in the order of expect(); sets stopReason() when the run must stop.
  std::vector<PeerNotice> review(double now);
  /// Why the run must stop (the first reason), if it must.
  const std::optional<std::string>& stopReason() const { return stop_; }

  /// Every peer is connected, or given up on (realtime).
  bool connected() const;
  PeerState state(const std::string& node) const;
  /// Whether the peer answers now (alive or restarted).
  bool alive(const std::string& node) const;
  /// The peer and its state for a message, e.g. "the front-end of robot b (/b/frontend): alive, pid 4242".
  std::string describe(const std::string& node) const;
  std::vector<std::string> nodes() const { return order_; }

 private:
  struct Peer {
    PeerRole role = PeerRole::Frontend;
    std::string what;
    PeerState state = PeerState::Waiting;
    PeerProbe last;            ///< the latest probe
    int pid = 0;               ///< of the latest life seen alive
    std::string uri;           ///< of the latest life seen alive
    int old_pid = 0;           ///< of the life before a restart
    bool ever_alive = false;
    bool ever_connected = false;  ///< alive and linked at least once
    bool linked = true;
    std::string link_hint;  ///< why its topics are not connected, when known
    bool given_up = false;        ///< realtime: never connected, the run went on without it
    double gone_since = 0.0;      ///< when it stopped answering (state Gone)
    double last_notice = -1e300;
    int restarts = 0, announced_restarts = 0;
    bool announced_gone = false;  ///< its silence was announced (its return is announced once too)
  };

  void reviewPeer(const std::string& node, Peer& p, double now, std::vector<PeerNotice>& out);
  void neverConnected(const std::string& node, Peer& p, double now, std::vector<PeerNotice>& out);
  void notAnswering(const std::string& node, Peer& p, double now, std::vector<PeerNotice>& out);
  void stop(const std::string& reason);
  bool due(Peer& p, double now);
  std::string detail(const Peer& p) const;

  RunMode mode_;
  PeerPolicyParams params_;
  std::optional<double> start_;
  std::map<std::string, Peer> peers_;
  std::vector<std::string> order_;
  std::optional<std::string> stop_;
  std::string master_uri_;
};

}  // namespace cosmo::live
