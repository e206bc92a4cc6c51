#include "cosmo/live/peer_watch.hpp"

#include <cmath>
#include <stdexcept>

#include "cosmo/live/peer_address_hint.hpp"

namespace cosmo::live {

namespace {

std::string seconds(double s) { return std::to_string(static_cast<long long>(std::floor(s + 0.5))) + " s"; }

bool answers(PeerState s) { return s == PeerState::Alive || s == PeerState::Restarted; }

}  // namespace

const char* peerStateName(PeerState state) {
  switch (state) {
    case PeerState::Waiting: return "waiting";
    case PeerState::Unreachable: return "unreachable";
    case PeerState::Alive: return "alive";
    case PeerState::Gone: return "gone";
    case PeerState::Restarted: return "restarted";
  }
  return "?";
}

PeerWatch::PeerWatch(RunMode mode, PeerPolicyParams params) : mode_(mode), params_(params) {}

void PeerWatch::expect(const std::string& node, PeerRole role, const std::string& what) {
  if (peers_.count(node)) throw std::invalid_argument("peer watch: " + node + " expected twice");
  Peer p;
  p.role = role;
  p.what = what;
  peers_[node] = p;
  order_.push_back(node);
}

void PeerWatch::start(double now) {
  if (!start_) start_ = now;
}

void PeerWatch::observe(const std::string& node, const PeerProbe& probe, double now) {
  const auto it = peers_.find(node);
  if (it == peers_.end()) return;
  Peer& p = it->second;
  p.last = probe;
  if (probe.answered) {
    if (p.ever_alive && (probe.pid != p.pid || probe.uri != p.uri)) {
      p.old_pid = p.pid;
      ++p.restarts;
      p.state = PeerState::Restarted;
    } else if (p.state != PeerState::Restarted) {
      p.state = PeerState::Alive;
    }
    p.ever_alive = true;
    p.pid = probe.pid;
    p.uri = probe.uri;
    p.ever_connected = p.ever_connected || p.linked;
  } else if (p.ever_alive) {
    if (p.state != PeerState::Gone) p.gone_since = now;
    p.state = PeerState::Gone;
  } else {
    p.state = probe.registered ? PeerState::Unreachable : PeerState::Waiting;
  }
}

void PeerWatch::setLinked(const std::string& node, bool linked, const std::string& hint) {
  const auto it = peers_.find(node);
  if (it == peers_.end()) return;
  it->second.linked = linked;
  if (!hint.empty() || linked) it->second.link_hint = hint;
  if (linked && answers(it->second.state)) it->second.ever_connected = true;
}

std::vector<PeerNotice> PeerWatch::review(double now) {
  std::vector<PeerNotice> out;
  if (!start_) return out;
  for (const std::string& node : order_) reviewPeer(node, peers_.at(node), now, out);
  return out;
}

void PeerWatch::reviewPeer(const std::string& node, Peer& p, double now, std::vector<PeerNotice>& out) {
  const std::string name = p.what + " (" + node + ")";
  const bool lockstep = mode_ == RunMode::Lockstep;
  const bool team_node = p.role == PeerRole::Frontend || p.role == PeerRole::Broker;
  if (!p.ever_connected) return neverConnected(node, p, now, out);
  if (p.state == PeerState::Gone) return notAnswering(node, p, now, out);
  if (p.restarts > p.announced_restarts) {
    p.announced_restarts = p.restarts;
    p.announced_gone = false;
    const std::string pids = "pid " + std::to_string(p.old_pid) + " -> " + std::to_string(p.pid);
    if (p.role == PeerRole::Player || (lockstep && team_node))
      return stop(name + " restarted (" + pids + "): its state is lost, the run cannot go on identically");
    out.push_back({false, name + " restarted (" + pids + ")" +
                              (p.role == PeerRole::Recorder
                                   ? ": it resumes from its journal; the front-ends resend what it did not acknowledge"
                                   : "")});
    return;
  }
  if (p.announced_gone) {
    p.announced_gone = false;
    out.push_back({false, name + " answers again (pid " + std::to_string(p.pid) + ")"});
  }
}

void PeerWatch::neverConnected(const std::string& node, Peer& p, double now, std::vector<PeerNotice>& out) {
  if (p.given_up) return;
  const std::string name = p.what + " (" + node + ")";
  const double limit = p.role == PeerRole::Recorder ? params_.recorder_timeout : params_.connect_timeout;
  const double waited = now - *start_;
  if (waited < limit) {
    // named from notice_period on (a peer is usually connected within a few seconds)
    if (waited >= params_.notice_period && due(p, now))
      out.push_back({false, "waiting for " + name + ": " + detail(p) + " (" + seconds(waited) + " of " +
                                seconds(limit) + ")"});
    return;
  }
  const std::string why = name + " did not connect within " + seconds(limit) + ": " + detail(p);
  if (mode_ == RunMode::Realtime && p.role == PeerRole::Frontend) {
    p.given_up = true;
    out.push_back({true, "going on without it: " + why +
                             ". Its robot's scans are not processed; a front-end that starts later joins from then"});
  } else if (mode_ == RunMode::Realtime && p.role == PeerRole::Broker) {
    p.given_up = true;
    out.push_back({true, "going on without the radio: " + why + ". No scans are exchanged until it connects"});
  } else {
    stop(why);
  }
}

void PeerWatch::notAnswering(const std::string& node, Peer& p, double now, std::vector<PeerNotice>& out) {
  const std::string name = p.what + " (" + node + ")";
  const double gone_for = now - p.gone_since;
  const bool lockstep = mode_ == RunMode::Lockstep;
  const bool announce = !p.announced_gone || due(p, now);
  if (!p.announced_gone) p.last_notice = now;
  p.announced_gone = true;
  switch (p.role) {
    case PeerRole::Frontend:
    case PeerRole::Broker:
      if (lockstep) {
        if (gone_for >= params_.death_grace)
          return stop(name + " died: " + detail(p) + "; a lockstep run cannot go on without it");
        if (announce)
          out.push_back({true, name + " does not answer: " + detail(p) + "; the run stops unless it answers within " +
                                   seconds(params_.death_grace)});
      } else if (announce) {
        out.push_back({true, name + " is gone since " + seconds(gone_for) + ": " + detail(p) +
                                 (p.role == PeerRole::Broker ? "; no scans are exchanged until it is back"
                                                             : "; waiting for the launch to respawn it")});
      }
      return;
    case PeerRole::Recorder:
      if (gone_for >= params_.recorder_timeout)
        return stop(name + " has been gone for " + seconds(gone_for) + " (not respawned?): " + detail(p));
      if (announce)
        out.push_back({true, name + " is gone since " + seconds(gone_for) + ": " + detail(p) +
                                 "; waiting for the launch to respawn it (up to " +
                                 seconds(params_.recorder_timeout) +
                                 "); the front-ends keep what it did not acknowledge"});
      return;
    case PeerRole::Player:
      if (gone_for >= params_.death_grace) return stop(name + " died: " + detail(p));
      return;
  }
}

void PeerWatch::stop(const std::string& reason) {
  if (!stop_) stop_ = reason;
}

bool PeerWatch::due(Peer& p, double now) {
  if (now - p.last_notice < params_.notice_period) return false;
  p.last_notice = now;
  return true;
}

bool PeerWatch::connected() const {
  for (const auto& [node, p] : peers_)
    if ((p.role == PeerRole::Frontend || p.role == PeerRole::Broker) && !p.ever_connected && !p.given_up)
      return false;
  return true;
}

PeerState PeerWatch::state(const std::string& node) const {
  const auto it = peers_.find(node);
  if (it == peers_.end()) throw std::invalid_argument("peer watch: unknown peer " + node);
  return it->second.state;
}

bool PeerWatch::alive(const std::string& node) const { return answers(state(node)); }

std::string PeerWatch::describe(const std::string& node) const {
  const auto it = peers_.find(node);
  if (it == peers_.end()) throw std::invalid_argument("peer watch: unknown peer " + node);
  return it->second.what + " (" + node + "): " + detail(it->second);
}

std::string PeerWatch::detail(const Peer& p) const {
  const PeerProbe& last = p.last;
  const std::string error = last.error.empty() ? "" : " (" + last.error + ")";
  switch (p.state) {
    case PeerState::Waiting:
      if (!master_uri_.empty()) return neverRegisteredHint(master_uri_);
      return "not registered with the master (not started yet, or it cannot reach the master: check its "
             "ROS_MASTER_URI)";
    case PeerState::Unreachable:
      return "registered at " + last.uri + ", but its XML-RPC server does not answer" + error + ": " +
             (last.hint.empty() ? "on one host a node that died; across hosts a wrong ROS_IP / ROS_HOSTNAME on its "
                                  "side, or a firewall"
                                : last.hint);
    case PeerState::Alive:
    case PeerState::Restarted:
      if (!p.linked)
        return "alive (pid " + std::to_string(p.pid) + " at " + p.uri + ") but its topics are not connected: " +
               (p.link_hint.empty() ? "across hosts, check ROS_IP / ROS_HOSTNAME on both sides" : p.link_hint);
      return "alive, pid " + std::to_string(p.pid);
    case PeerState::Gone:
      if (!last.registered) return "pid " + std::to_string(p.pid) + " is no longer registered with the master";
      if (last.uri != p.uri)
        return "pid " + std::to_string(p.pid) + " was replaced at the master by " + last.uri + ", which does not answer" +
               error;
      return "pid " + std::to_string(p.pid) + " at " + p.uri + " does not answer" + error +
             (last.refused ? ": the process has ended" : "");
  }
  return "";
}

}  // namespace cosmo::live
