#pragma once
// Each robot's LOAM odometry computed on its own thread from its own reader of the robot's scans, as far ahead of
// the team as the CPU allows. A robot's odometry depends only on its own scans, so it need not wait for the
// team's sequence order: while only one robot is on the move at the start of a sequence, the others' odometry is
// already being computed. The team (radio, place recognition, registration) then consumes the results in
// sequence order with next(). Each worker reads its scans through a one-robot MergedScanStream (same time shift,
// same dropped scans as the team's stream) and feeds them to its own LoamOdometry in order, so every result is
// exactly what RobotFrontend's own LoamOdometry would compute: the output does not depend on threads or timing.
// Results are small (a pose and diagnostics), so a worker never waits for the team.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/pipeline/scan_stream.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

namespace cosmo::pipeline {

class OdometryRunAhead {
 public:
  /// `sources`: robot -> a reader of the same scans the team's stream holds for that robot (a second reader of
  /// the same bag); `timing` as for the team's MergedScanStream. Starts one worker thread per robot.
  OdometryRunAhead(std::map<char, std::unique_ptr<ScanSource>> sources, const SequenceTiming& timing,
                   const LoamParams& params);
  ~OdometryRunAhead();
  OdometryRunAhead(const OdometryRunAhead&) = delete;
  OdometryRunAhead& operator=(const OdometryRunAhead&) = delete;

  /// The odometry of `robot`'s next scan, which must carry `stamp` (sequence time); waits until it is computed.
  /// Throws std::logic_error when the worker's scan differs (the readers disagree) or it has no scan left, and
  /// rethrows a worker's exception.
  OdometryResult next(char robot, StampNs stamp);

 private:
  struct Computed {
    StampNs stamp;
    OdometryResult result;
  };
  struct Worker {
    Worker(MergedScanStream s, const LoamParams& params) : stream(std::move(s)), odometry(params) {}
    MergedScanStream stream;
    LoamOdometry odometry;
    std::deque<Computed> results;
    bool done = false;  ///< the worker's stream is exhausted (or it failed)
    std::exception_ptr error;
    std::mutex mutex;
    std::condition_variable ready;
    std::thread thread;
  };
  void run(Worker& w);

  std::map<char, std::unique_ptr<Worker>> workers_;
  std::atomic<bool> stop_{false};
};

}  // namespace cosmo::pipeline
