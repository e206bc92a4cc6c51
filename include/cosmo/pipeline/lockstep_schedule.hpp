#pragma once
// The team's event order, one rule for both drivers: TeamRun runs it in one thread, the lockstep player drives the
// ROS nodes through it (the front-ends, the comm_broker and the recorder report their progress back to it).
//
// Radio steps lie on a grid (team_radio.hpp). Before a scan stamped s is handed to its robot's front-end, every
// radio step at or before s runs and the scans it delivered are processed by their receivers; then the scan.
// Scans of different robots between two radio steps do not interact (deliveries and the radio's robot states
// change only at steps), so they may be processed in parallel; a robot's own scans stay in order.
//
// The schedule holds no clock and no threads: a driver asks what must happen before the next scan, does it, and
// reports what happened. Every method is a plain state update, so the player's protocol is tested without ROS.
#include <cstdint>
#include <map>
#include <vector>

#include "cosmo/common/time.hpp"

namespace cosmo::pipeline {

/// What a front-end reports after every scan and every delivery it processed (FrontendAck in ROS).
struct FrontendProgress {
  StampNs last_scan = 0;            ///< the latest own scan processed (sequence time)
  std::uint32_t scans = 0;          ///< own scans processed: the robot is on for the radio from the first
  std::uint32_t received = 0;       ///< teammate scans processed (deliveries)
  std::uint32_t keyframes = 0;      ///< keyframes offered to the radio
  std::uint32_t loop_closures = 0;  ///< accepted loop closures sent to the recorder
  std::uint64_t seq = 0;            ///< the last measurement number sent to the recorder (0: none)
};

/// A request to step the radio through `through`: the robots' states, and the keyframe offers that must have
/// reached the radio first.
struct RadioStepOrder {
  StampNs through = 0;
  std::vector<char> robots;
  std::vector<bool> on;                  ///< per robot: processed at least one scan
  std::vector<std::uint32_t> keyframes;  ///< per robot: keyframes offered so far
};

class LockstepSchedule {
 public:
  /// `with_radio`: false when no radio runs (scans then only keep their robot's order).
  LockstepSchedule(std::vector<char> robots, bool with_radio);

  /// Whether a radio runs (a driver finds out once the nodes are connected).
  void useRadio(bool with_radio) { with_radio_ = with_radio; }

  /// What must happen before `robot`'s scan at `stamp` is handed over, in this order.
  struct BeforeScan {
    bool wait_for_scans = false;  ///< every scan handed over so far processed (scansProcessed())
    bool step_radio = false;      ///< the radio stepped through the scan's stamp, its deliveries processed
  };
  BeforeScan beforeScan(char robot, StampNs stamp) const;
  /// The scan was handed to its front-end (its report may have come already: reports and hand-overs are matched
  /// by stamp, in either order).
  void scanHandedOver(char robot, StampNs stamp);

  /// A front-end's report.
  void frontendReported(char robot, const FrontendProgress& progress);
  /// The radio ran its steps through the requested stamp: `next_step` is where the next one lies (a scan stamped
  /// at or after it needs a radio step first), `delivered` the scans delivered so far, per receiver.
  void radioStepped(StampNs next_step, const std::map<char, std::uint32_t>& delivered);
  /// The recorder holds every measurement of `robot` numbered up to `acked`.
  void recorderReported(char robot, std::uint64_t acked);

  /// Every scan handed over was processed.
  bool scansProcessed() const;
  /// Robots with a scan handed over and not processed yet.
  std::vector<char> robotsBehind() const;
  /// Gives up waiting for the scans handed over so far (a silent front-end).
  void stopWaitingForScans() { handed_over_.clear(); }
  /// Every scan the radio delivered was processed by its receiver.
  bool deliveriesProcessed() const;
  /// A recorder is part of the run: recorderComplete() waits for it also before it reported.
  void expectRecorder() { recorder_reported_ = true; }
  /// The recorder holds every measurement the front-ends reported sending (true before it reported at all, unless
  /// expected: a run without a recorder).
  bool recorderComplete() const;
  /// Robots whose measurements the recorder does not hold yet.
  std::vector<char> robotsNotRecorded() const;
  /// The request that steps the radio through `through`.
  RadioStepOrder radioStepOrder(StampNs through) const;

  const std::vector<char>& robots() const { return robots_; }
  const FrontendProgress& progress(char robot) const;

 private:
  std::vector<char> robots_;
  bool with_radio_;
  bool radio_stepped_ = false;
  StampNs next_step_ = 0;
  std::map<char, StampNs> handed_over_;  ///< the latest scan handed over and not processed, per robot
  std::map<char, FrontendProgress> progress_;
  std::map<char, std::uint32_t> delivered_;
  bool recorder_reported_ = false;
  std::map<char, std::uint64_t> recorded_;  ///< the recorder's acked, per robot
};

}  // namespace cosmo::pipeline
