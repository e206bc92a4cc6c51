#pragma once
// Temporal synchronization of the trials of a sequence (spec section 3). The anchor trial starts at t*, its
// own first stamp; every other trial i is shifted as a whole so that it starts at t* + Δi, Δi ~ N(0, σ)
// (σ = 40 s by default), drawn in trial order from the "trial_offsets" stream of the sequence seed. Offsets are
// rounded to whole milliseconds. When a shifted trial would start before 1 s after the epoch (synthetic trials
// stamped from 0), every trial (anchor included) moves later by the same amount so that stamps stay positive.
//
// A robot is off before its first measurement; after its last it stays on, stationary at its final pose,
// until the sequence ends (the last stamp of any trial).
#include <cstdint>
#include <vector>

#include "cosmo/common/time.hpp"

namespace cosmo::sequence {

/// First and last scan stamps of one trial, in the trial's own (recorded) time.
struct TrialSpan {
  char robot = 'a';
  StampNs first = 0;
  StampNs last = 0;
};

/// One trial's shift into sequence time.
struct TrialTiming {
  char robot = 'a';
  StampNs first = 0;           ///< recorded first stamp
  StampNs last = 0;            ///< recorded last stamp
  std::int64_t offset_ns = 0;  ///< sequence stamp = recorded stamp + offset_ns

  StampNs toSequence(StampNs recorded) const;
  StampNs toRecorded(StampNs sequence) const;
  StampNs start() const { return toSequence(first); }  ///< first measurement, sequence time
  StampNs end() const { return toSequence(last); }     ///< last measurement, sequence time
};

class SequenceTiming {
 public:
  SequenceTiming() = default;
  /// Draw the offsets. `spans` in trial order; `anchor` must be one of them; sigma_s >= 0.
  static SequenceTiming synchronize(const std::vector<TrialSpan>& spans, char anchor, double sigma_s,
                                    std::uint64_t seed);

  const std::vector<TrialTiming>& trials() const { return trials_; }
  const TrialTiming& of(char robot) const;  ///< throws for an unknown robot
  StampNs start() const { return start_; }  ///< earliest first measurement over all trials
  StampNs end() const { return end_; }      ///< latest last measurement (the sequence ends here)
  double durationSeconds() const { return toSeconds(end_ - start_); }
  /// Robot state at sequence time `t`: off before its first measurement, on from then to the end.
  bool isOn(char robot, StampNs t) const { return t >= of(robot).start(); }

 private:
  std::vector<TrialTiming> trials_;
  StampNs start_ = 0, end_ = 0;
};

}  // namespace cosmo::sequence
