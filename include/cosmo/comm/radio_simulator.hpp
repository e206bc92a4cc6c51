#pragma once
// The paper's Algorithm 1 (Simulate Communication), one step of delta at a time:
//   1. initialize new communications among available robots (on, not communicating, within d_init, with a
//      keyframe the other has not received yet); an attempt succeeds when its connectivity sample succeeds;
//   2. for every active communication sample C ~ Bernoulli(phi(d)) and integrate T = (B / I) * C * delta,
//      I = 1 + other active communications with an endpoint within d_intf of either endpoint;
//   3. terminate: delivered when the integrated bytes reach the payload, timed out after T (RadioParams).
// Connectivity, the throughput alone on the channel (B) and the latency (0) come from the link model
// (comm/link_model.hpp): phi(d), or a radio trace inside its windows. With a latency L the sender and receiver are
// free once the last byte is sent; the transfer reaches the receiver (step() returns it, Transfer::received) at the
// first step at or after end + L.
//
// Decisions (documented in the README):
// * Who sends: a pair runs one communication in one direction. The sender is the robot with more keyframes
//   not yet delivered to the other; a tie is broken by a fair coin from the seeded RNG. A pair where neither
//   has anything new to send does not try to connect.
// * Pair order: the candidate pairs of a step are tried in a seeded random order (no bias for robot "a").
// * The connectivity sample that initialized a communication is also its first step's sample (one sample
//   per pair per step), so a new communication already carries data in the step it started.
// * Interference is counted over the communications active after initialization, before any terminates in
//   that step (all communications of a step see the same set).
// * Scan selection: the sender picks uniformly at random among its offered keyframes not yet delivered to
//   that receiver (a timed-out keyframe can be picked again).
// * Robot state: a robot is off until setRobotState(.., on = true); its last state persists, so a robot whose
//   trial ended stays on and stationary when the caller stops updating it. An active communication whose
//   endpoint is off gets connectivity 0.
// * Paper size model: f ~ N(0.653, 0.04) is drawn per (robot, keyframe) from a generator seeded by
//   (seed, robot, keyframe), so sizes do not depend on call order; f is clamped to >= 0.01.
// Determinism: every other draw comes from one std::mt19937_64 seeded with `seed`, robots are iterated in
// sorted order; the same calls give the same transfers.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "cosmo/comm/connectivity.hpp"
#include "cosmo/comm/link_model.hpp"
#include "cosmo/comm/radio_params.hpp"
#include "cosmo/comm/transfer.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::comm {

/// A communication in progress (for link display and statistics).
struct ActiveCommunication {
  char sender = 0;
  char receiver = 0;
  std::size_t keyframe = 0;
  double start = 0.0;
  std::size_t bytes = 0;         ///< payload size
  double bytes_delivered = 0.0;  ///< integrated so far
  double last_progress = 0.0;    ///< time of the last step that delivered bytes
  double distance = 0.0;         ///< distance (m) at the last step
  int interference = 1;          ///< I_ab at the last step
  double throughput_Bps = 0.0;   ///< bytes per second in the last step (0 when the sample failed)
  double capacity_Bps = 0.0;     ///< the link's throughput alone on the channel, at its last connected sample
  double latency = 0.0;          ///< the link's latency (s) at its last connected sample
  bool used_trace = false, used_distance = false;  ///< which link models answered its samples
};

/// Summary counters of a run.
struct RadioStats {
  std::uint64_t steps = 0;
  std::uint64_t init_attempts = 0;  ///< connectivity samples of pairs trying to start
  std::uint64_t initiated = 0;      ///< communications started
  std::uint64_t delivered = 0;
  std::uint64_t timed_out = 0;
  std::uint64_t link_samples = 0;  ///< connectivity samples of active communications (step 2)
  std::uint64_t link_successes = 0;
  double bytes_delivered = 0.0;    ///< payload bytes of delivered transfers
  double bytes_transmitted = 0.0;  ///< all bytes that got through, also of transfers that timed out
  std::uint64_t keyframes_offered = 0;
  /// With a radio trace: connectivity samples (init attempts and links) answered by its windows, and by phi(d)
  /// outside them (the fallback).
  std::uint64_t trace_samples = 0, fallback_samples = 0;
  std::uint64_t in_flight = 0;  ///< sent in full, not yet received (a trace's latency)
};

class RadioSimulator {
 public:
  /// `robots`: the team's ids (sorted and de-duplicated internally). Throws std::invalid_argument on invalid
  /// parameters or an empty team, std::runtime_error (file and line) when the radio trace names another robot.
  RadioSimulator(const RadioParams& p, std::vector<char> robots, std::uint64_t seed);

  /// Position (world frame, m) and on/off of a robot; call before each step (or when it changes).
  void setRobotState(char robot, const Eigen::Vector3d& position, bool on);
  /// A keyframe the robot can send. `payload_bytes`: its real compressed size (RealCompressed model).
  /// `raw_bytes`: its uncompressed size S = 12 * points, the base of the paper's model; when 0 the paper's
  /// model uses payload_bytes / size_factor_mean as S. Offering the same keyframe again updates its sizes.
  void offerKeyframe(char robot, std::size_t keyframe, std::size_t payload_bytes, std::size_t raw_bytes = 0);
  /// Advance one step of delta ending at time t (s); returns the transfers that ended in it, in order of
  /// their senders then receivers. Throws std::invalid_argument when t is not after the previous step.
  std::vector<Transfer> step(double t);
  /// Time of the next step on the grid start + k * delta (0 + k * delta unless setStartTime was called or a
  /// step was taken off the grid, which restarts the grid there).
  double nextStepTime() const { return start_time_ + static_cast<double>(next_index_) * params_.step; }
  /// Restart the step grid at t.
  void setStartTime(double t);
  /// Radio time of the radio trace's time 0 (default 0).
  void setTraceOrigin(double t) { link_.setTraceOrigin(t); }
  /// The stamp of radio time 0, for the transfer log (default 0: radio time is UNIX time).
  void setTimeOrigin(StampNs origin) { time_origin_ = origin; }
  StampNs timeOrigin() const { return time_origin_; }
  /// Keep every connectivity sample (linkRecords(), RadioTrace::fromRecords: a trace of this run).
  void recordLinks(bool on) { link_.setRecording(on); }
  const std::vector<LinkRecord>& linkRecords() const { return link_.records(); }

  const RadioParams& params() const { return params_; }
  const std::vector<char>& robots() const { return robot_ids_; }
  const RadioStats& stats() const { return stats_; }
  /// Connectivity per pair over the steps so far (comm/connectivity.hpp; LinkModel::connected), with the radio's
  /// time origin, d_init and trace.
  Connectivity connectivity() const;
  /// Every finished transfer so far, in the order they ended.
  const std::vector<Transfer>& transferLog() const { return log_; }
  const std::vector<ActiveCommunication>& activeCommunications() const { return active_; }
  /// The communications that carried (or tried to carry) data in the last step, including those that ended
  /// in it (for link display: a short transfer starts and ends within one step).
  const std::vector<ActiveCommunication>& lastStepCommunications() const { return last_step_; }
  /// Whether `receiver` already got `sender`'s keyframe.
  bool wasDelivered(char sender, char receiver, std::size_t keyframe) const;
  /// Keyframes of `sender` not yet delivered to `receiver`.
  std::size_t undeliveredCount(char sender, char receiver) const;
  /// Payload size the simulation uses for an offered keyframe (0 when not offered).
  std::size_t payloadSize(char robot, std::size_t keyframe) const;
  bool isOn(char robot) const;
  Eigen::Vector3d position(char robot) const;

 private:
  struct Offer {
    std::size_t payload_bytes = 0;  ///< size under the configured size model
  };
  struct Robot {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    bool on = false;
    bool busy = false;
    std::map<std::size_t, Offer> offers;
    std::map<char, std::set<std::size_t>> delivered_to;  ///< receiver -> keyframes delivered
  };

  Robot& robot(char id, const char* what);
  const Robot& robot(char id, const char* what) const;
  void initializeNewCommunications(double t);
  void updateActiveCommunications(double t);
  std::vector<Transfer> terminateCommunications(double t);
  std::size_t pickKeyframe(const Robot& sender, char receiver);
  LinkSample sampleLink(char a, char b, double t, double distance);
  void received(const Transfer& x);

  RadioParams params_;
  std::vector<char> robot_ids_;
  std::map<char, Robot> robots_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;
  LinkModel link_;
  ConnectivityTracker connectivity_;
  std::vector<Transfer> in_flight_;  ///< sent in full; `received` holds the time they arrive
  StampNs time_origin_ = 0;
  std::vector<ActiveCommunication> active_;
  std::vector<ActiveCommunication> last_step_;
  std::vector<bool> new_this_step_;  ///< parallel to active_: started in the current step
  std::vector<Transfer> log_;
  RadioStats stats_;
  double start_time_ = 0.0;
  std::uint64_t next_index_ = 0;
  bool stepped_ = false;
  double last_time_ = 0.0;
};

}  // namespace cosmo::comm
