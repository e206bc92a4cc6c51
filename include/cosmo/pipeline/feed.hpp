#pragma once
// Feeding a TeamRun with a sequence's scans: one policy, the three feeders and the choice among them, one end of
// a run.
//   replay     a previous comm model's run computed the robots' own results (LOAM odometry, keyframe scans),
//              which do not depend on the comm model: they are fed again (ComputedScans);
//   run ahead  LOAM odometry: each robot's LOAM and keyframes on its own thread (OdometryRunAhead), the team on
//              this one; the results are kept for the next comm model when asked;
//   serial     everything on this thread, scan by scan (reference odometry, whose poses take the points; or asked).
// The end: the scans stamped up to `end` (sequence time) are fed, then TeamRun::finish(end) runs the radio through
// it and waits for every registration. The output is the same byte for byte whichever feeder ran.
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "cosmo/frontend/kept_scan.hpp"
#include "cosmo/frontend/odometry_run_ahead.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::pipeline {

/// The robots' own results of a run, kept for the next comm model; their keyframe scans wait in a spill file
/// (KeptScan), not in memory.
struct ComputedScans {
  explicit ComputedScans(std::shared_ptr<frontend::SpillFile> spill_file = nullptr) : spill(std::move(spill_file)) {}
  std::vector<frontend::AheadScan> scans;
  std::vector<std::shared_ptr<const frontend::KeptScan>> keyframes;  ///< one per keyframe of `scans`, in order
  std::shared_ptr<frontend::SpillFile> spill;
  std::map<char, std::size_t> dropped;
  bool ready = false;

  void keep(const frontend::AheadScan& s);
};

/// How a run was fed: scans dropped per robot (stamps not increasing), and where the team's thread spent its
/// wall time by FeedPlan::wall_clock (instrumentation only: nothing depends on it).
struct FeedFigures {
  std::map<char, std::size_t> dropped;
  double wait_odometry_s = 0.0, team_work_s = 0.0, finish_s = 0.0;
};

/// What to feed: the sequence, its end, and how the robots' scans are read.
struct FeedPlan {
  const sequence::SequenceConfig* config = nullptr;
  const sequence::SequenceTiming* timing = nullptr;
  const std::map<char, Trajectory>* references = nullptr;
  StampNs end = 0;
  /// A reader of each robot's scans in recorded time (trials::openTrialSources).
  std::function<std::map<char, std::unique_ptr<sequence::ScanSource>>()> sources;
  bool serial = false;  ///< everything on this thread even with LOAM odometry
  /// Keep the robots' results for the next comm model (nullptr: do not); replayed when ready.
  ComputedScans* computed = nullptr;
  /// Called after each scan fed, with its stamp (progress lines).
  std::function<void(StampNs)> progress;
  /// A wall clock in seconds for FeedFigures, passed in by the driver (the core reads no clock); none: they stay 0.
  std::function<double()> wall_clock;
};

/// Feeds `run` by the policy above and finishes it at `plan.end`.
FeedFigures feed(TeamRun& run, const FeedPlan& plan);

}  // namespace cosmo::pipeline
