#pragma once
// The whole team in one process, the offline driver of the shared object graph (design.md principle 4):
// one RobotFrontend per robot, the RadioSimulator (comm) between them and the DatasetRecorder (dataset)
// gathering every measurement. Deterministic: one order of events (below), all randomness from the seed.
//
// Event order (LockstepSchedule, which the lockstep player drives the ROS nodes through): radio steps lie on the
// grid origin + k * delta. Before a scan stamped s is processed, every radio step at a time <= s runs (advanceRadio,
// team_radio.hpp, which the comm_broker node shares): robot states are set (on once the robot processed its first scan,
// position from its reference trajectory held at the ends, or its odometry position without one), the step runs, and
// each delivered scan is handed to its receiver at the step time (the time its loop closures are computed at). Then the
// scan goes through its robot's front-end; a new keyframe is offered to the radio and recorded, accepted loop closures
// are recorded.
//
// Registration threads (TeamRunParams::registration_threads > 0): the loop-closure registrations run on a
// RegistrationPool while this thread goes on with the radio, place recognition and the next scans. Nothing the
// team does depends on a registration's verdict except what is recorded, so the recorder calls (keyframes and loop
// closures) wait in a queue in the order the single-threaded run makes them and are made, in that order, as soon
// as the registrations before them are done: the same JRL, byte for byte. counts() and on_loop_closure lag
// behind until finish(), which waits for every registration.
//
// Payload: with the paper's size model the delivered scan is the sender's own KeptScan (xz is lossless, so
// decompress(compress(scan)) is the same points), so the team keeps each scan and its features once, on disk;
// with the real size model the radio's PayloadStore (comm/payload_store.hpp, as in the comm_broker node) keeps
// the xz payload when offered and the receiver gets its decompressed copy.
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "cosmo/comm/payload_store.hpp"
#include "cosmo/comm/radio_params.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/pipeline/lockstep_schedule.hpp"
#include "cosmo/frontend/robot_frontend.hpp"

namespace cosmo::pipeline {

struct TeamRunParams {
  /// frontend.odometry: loam, or reference (perfect odometry: tests, and isolating loop-closure errors; the
  /// references are whole, so a robot's pose is held at their ends, and robots without one use LOAM).
  frontend::FrontendParams frontend;
  comm::RadioParams radio = comm::RadioParams::wifi();
  dataset::NoiseModels noise;
  dataset::OutlierRule outlier_rule = dataset::OutlierRule::Fidelity;
  /// Threads that run the loop-closure registrations (0: inline on the caller's thread). Same output either way.
  unsigned registration_threads = 0;
  /// Extra lines of the dataset's metadata (DatasetRecorder::setMetadata), e.g. the sequence's reference offset.
  std::vector<std::pair<std::string, std::string>> metadata;
};

/// Running totals for progress output.
struct TeamCounts {
  std::size_t scans = 0;
  std::size_t keyframes = 0;
  std::size_t intra_accepted = 0, intra_rejected = 0;
  std::size_t inter_accepted = 0, inter_rejected = 0;
  std::size_t transfers_delivered = 0, transfers_timed_out = 0;
  std::size_t recorder_rejected = 0;  ///< measurements the recorder refused (logged)
};

class TeamRun {
 public:
  /// `references`: robot -> sensor trajectory in the world frame, sequence time (an empty one: no reference).
  /// `time_origin`: sequence time of radio time 0 (the sequence start).
  TeamRun(std::string dataset_name, std::map<char, Trajectory> references, const TeamRunParams& params,
          std::uint64_t radio_seed, StampNs time_origin);

  /// Runs the radio through `scan.stamp`, then the scan through `robot`'s front-end (RobotFrontend::add: its
  /// points, or prepared ahead by OdometryRunAhead).
  void add(char robot, const frontend::OwnScan& scan);
  /// Runs the radio through `end` (the sequence end) so late transfers are delivered, and waits for every
  /// pending registration (the recorder is complete afterwards).
  void finish(StampNs end);
  /// Records what is pending, waiting for the registrations (finish() does it too).
  void drain();
  /// The registration threads (nullptr without).
  const frontend::RegistrationPool* registrationPool() const { return pool_.get(); }

  const TeamRunParams& params() const { return params_; }
  /// The recorder; with registration threads complete only after finish() (or drain()).
  const dataset::DatasetRecorder& recorder() const { return recorder_; }
  const comm::RadioSimulator& radio() const { return radio_; }
  const frontend::RobotFrontend& frontend(char robot) const;
  const TeamCounts& counts() const { return counts_; }
  std::vector<char> robots() const;
  /// Recorder messages (refused measurements), for the log.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// Called for every loop-closure attempt (progress, visualisation); optional.
  std::function<void(const frontend::LoopClosureAttempt&)> on_loop_closure;

 private:
  void advanceRadioTo(StampNs t);
  /// What the team's event order (LockstepSchedule) runs before `robot`'s scan at `stamp`: the due radio steps.
  void beforeScan(char robot, StampNs stamp);
  frontend::RobotFrontend& frontendFor(char robot);
  /// Bookkeeping of a step: the keyframe recorded and offered to the radio, loop closures recorded in order.
  void take(const frontend::RobotFrontend& fe, frontend::Step step);
  void record(const frontend::LoopClosureAttempt& a);
  void recordKeyframe(const frontend::KeyframeRecord& kf);
  /// Records the queue's front while it is ready (`wait`: waits for every pending registration), and waits for the
  /// front while more than kMaxPending registrations are pending.
  void flush(bool wait);

  /// A recorder call in the single-threaded order: a keyframe, or a loop closure whose registration may be pending.
  struct PendingRecord {
    std::optional<frontend::KeyframeRecord> keyframe;
    frontend::PendingLoopClosure loop_closure;
  };
  /// Registrations the team may run ahead of (bounds the lag of counts() and the queue's memory).
  static constexpr std::size_t kMaxPending = 64;

  TeamRunParams params_;
  std::map<char, std::unique_ptr<frontend::RobotFrontend>> frontends_;
  comm::RadioSimulator radio_;
  LockstepSchedule schedule_;
  dataset::DatasetRecorder recorder_;
  comm::PayloadStore payloads_;
  StampNs origin_;
  TeamCounts counts_;
  std::vector<std::string> warnings_;
  std::shared_ptr<frontend::RegistrationPool> pool_;
  std::deque<PendingRecord> pending_;
  std::size_t pending_loop_closures_ = 0;
};

}  // namespace cosmo::pipeline
