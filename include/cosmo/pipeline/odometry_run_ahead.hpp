#pragma once
// Each robot's LOAM odometry computed on its own thread from its own reader of the robot's scans, as far ahead of
// the team as the CPU allows. A robot's odometry depends only on its own scans, so it need not wait for the
// team's sequence order: while only one robot is on the move at the start of a sequence, the others' odometry is
// already being computed. Each worker reads its scans through a one-robot MergedScanStream (same time shift,
// same dropped scans as a team stream) and feeds them to its own LoamOdometry in order, so every result is
// exactly what RobotFrontend's own LoamOdometry would compute: the output does not depend on threads or timing.
//
// The team consumes the results in sequence order with next() (stamps merged as MergedScanStream does: earliest
// first, ties to the lower robot id), so the team needs no reader of its own. Only keyframe scans carry their
// points: a worker runs the front-end's keyframe rule (Keyframer, same distance) on its odometry and hands over
// the scans it keeps; any other scan arrives as its stamp alone (RobotFrontend reads a scan's points only for a
// keyframe). A worker holds at most `max_held_scans` scans the team has not taken yet and waits beyond that, so
// memory stays bounded while the small results run ahead.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "cosmo/odometry/keyframer.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/pipeline/scan_stream.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

namespace cosmo::pipeline {

/// One robot's next scan as the team takes it.
struct RunAheadScan {
  char robot = 0;
  std::shared_ptr<const Scan> scan;  ///< the whole scan for a keyframe; otherwise its stamp only (no points)
  bool keyframe = false;             ///< the worker's keyframe rule kept this scan
  OdometryResult odometry;
};

class OdometryRunAhead {
 public:
  /// `sources`: robot -> its scans in recorded time; `timing` as for a team MergedScanStream; `keyframe_distance`:
  /// the front-end's (FrontendParams::keyframe_distance). Starts one worker thread per robot.
  OdometryRunAhead(std::map<char, std::unique_ptr<ScanSource>> sources, const SequenceTiming& timing,
                   const LoamParams& params, double keyframe_distance, std::size_t max_held_scans = 64);
  ~OdometryRunAhead();
  OdometryRunAhead(const OdometryRunAhead&) = delete;
  OdometryRunAhead& operator=(const OdometryRunAhead&) = delete;

  /// The team's next scan in sequence time; false when every robot's scans are done. Waits for the workers it
  /// needs; rethrows a worker's exception.
  bool next(RunAheadScan& out);
  /// Scans dropped because their stamp did not increase, per robot (complete once next() returned false).
  std::map<char, std::size_t> dropped() const;

 private:
  struct Worker {
    Worker(MergedScanStream s, const LoamParams& params, double keyframe_distance)
        : stream(std::move(s)), odometry(params), keyframer(keyframe_distance) {}
    MergedScanStream stream;
    LoamOdometry odometry;
    Keyframer keyframer;
    std::deque<RunAheadScan> results;
    std::size_t held = 0;  ///< results in the queue that carry a whole scan
    bool done = false;     ///< the worker's stream is exhausted (or it failed)
    bool stop = false;
    std::exception_ptr error;
    mutable std::mutex mutex;
    std::condition_variable changed;
    std::thread thread;
  };
  void run(Worker& w);

  std::map<char, std::unique_ptr<Worker>> workers_;
  std::size_t max_held_;
};

}  // namespace cosmo::pipeline
