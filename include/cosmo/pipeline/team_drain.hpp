#pragma once
// The end of a real-time run: whether each front-end is done with everything it was given, so that the run ends
// only once every measurement made is with the recorder. A front-end reports (FrontendAck) after every scan and
// delivery and once a second between them; it is drained when
// - its latest report is fresh (younger than `fresh` s: a front-end busy in a long registration does not report),
// - it shows no scan waiting,
// - its counters (scans, deliveries, keyframes, loop closures, measurement number) have not moved for `quiet` s (a
//   delivery still on its way would move them),
// - and the recorder holds every measurement it sent.
// Wall times are passed in; no clock.
#include <map>

#include "cosmo/pipeline/lockstep_schedule.hpp"

namespace cosmo::pipeline {

class TeamDrain {
 public:
  explicit TeamDrain(double quiet = 2.0, double fresh = 1.5) : quiet_(quiet), fresh_(fresh) {}

  /// A report of `robot` at `now`, with `queued` scans waiting.
  void reported(char robot, const FrontendProgress& progress, std::uint32_t queued, double now);
  /// Whether `robot` is drained at `now`, the recorder holding its measurements up to `recorder_acked`.
  bool drained(char robot, std::uint64_t recorder_acked, double now) const;
  /// The last measurement number `robot` reported (0: none).
  std::uint64_t lastSeq(char robot) const;

 private:
  struct Robot {
    FrontendProgress progress;
    std::uint32_t queued = 0;
    double reported_at = 0.0, changed_at = 0.0;
  };
  double quiet_, fresh_;
  std::map<char, Robot> robots_;
};

}  // namespace cosmo::pipeline
