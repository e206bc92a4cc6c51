#pragma once
// Each robot's robot-local work computed on its own thread from its own reader of the robot's scans, as far ahead
// of the team as the CPU allows: LOAM odometry, the keyframer and every keyframe's dewarped scan (KeyframeTaker).
// None of it depends on the other robots, so it need not wait for the team's sequence order: while only one robot
// is on the move at the start of a sequence, the others' odometry is already being computed, and the team's thread
// (radio, place recognition, pairwise registration, recording) never decodes a scan. next() hands the results over in
// the team's sequence order (MergedScanStream's: stamp, ties to the lower robot id). Each worker reads its scans
// through a one-robot MergedScanStream (same time shift, same dropped scans as the team's stream would have) and feeds
// them to its own objects in order, so every result is exactly what the RobotFrontend's own would compute: the output
// does not depend on threads or timing (test TeamRun.OdometryOnWorkerThreadsGivesTheSameJrl). A worker stays at most
// kMaxAhead scans ahead of the team (a bound on the keyframe scans waiting in memory). Admission keeps the team's
// thread, the serial part of a run, from being starved: a worker starts a scan only while fewer threads than cores are
// busy, counting the team's thread whenever it is not waiting for a result, and the worker the team waits for always
// may: with more threads than cores the workers would run ahead at the team's expense and leave the team's
// loop-closure work, concentrated late in a sequence, to run alone on one core at the end. Registration features are
// left to the registrations (on the team's thread, or on TeamRun's RegistrationPool), which compute them only for
// the keyframes that become loop-closure candidates: computing them ahead for every keyframe would cost more CPU in
// all, and the CPU in all is what bounds a run on two cores. The pool's threads are not counted by the admission rule
// (see team_run.hpp).
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/frontend/keyframe_taker.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::frontend {

/// One scan's robot-local results (the scan itself is not kept, only a keyframe's dewarped scan).
struct AheadScan {
  char robot = 'a';
  StampNs stamp = 0;  ///< sequence time
  odometry::OdometryResult odometry;
  std::shared_ptr<const Scan> keyframe_scan;  ///< the keyframe scan when the scan is a keyframe
};

class OdometryRunAhead {
 public:
  /// Results a worker may hold before it waits for the team (about 100 s of a 10 Hz sensor).
  static constexpr std::size_t kMaxAhead = 1000;

  /// `sources`: robot -> a reader of the robot's scans in recorded time; `timing` as for the team's
  /// MergedScanStream; `references`: robot -> its sensor reference trajectory in sequence time (keyframe dewarping,
  /// as the robot's RobotFrontend holds it; a robot missing or empty: dewarped with odometry); `cores`: how many
  /// threads may be busy at once (0: the machine's hardware concurrency). Starts one worker thread per robot.
  OdometryRunAhead(std::map<char, std::unique_ptr<sequence::ScanSource>> sources, const sequence::SequenceTiming& timing,
                   const FrontendParams& params, const std::map<char, Trajectory>& references, unsigned cores = 0);
  ~OdometryRunAhead();
  OdometryRunAhead(const OdometryRunAhead&) = delete;
  OdometryRunAhead& operator=(const OdometryRunAhead&) = delete;

  /// The next scan of any robot in sequence order; waits until it is computed. False when every robot's scans
  /// are done. Rethrows a worker's exception.
  bool next(AheadScan& out);
  /// Stops and joins the workers (idempotent; next() then returns what was computed before).
  void stop();
  /// Scans each robot's stream dropped (stamps not increasing); complete once the workers finished or stopped.
  std::map<char, std::size_t> dropped();

 private:
  struct Worker {
    Worker(char r, sequence::MergedScanStream s, const FrontendParams& params, Trajectory ref)
        : robot(r), stream(std::move(s)), odometry(params.loam), taker(params), reference(std::move(ref)) {}
    char robot;
    sequence::MergedScanStream stream;
    odometry::LoamOdometry odometry;
    KeyframeTaker taker;
    Trajectory reference;
    std::deque<AheadScan> results;
    bool done = false;  ///< the worker's stream is exhausted (or it failed, or was stopped)
    std::map<char, std::size_t> dropped;
    std::exception_ptr error;
    std::mutex mutex;
    std::condition_variable ready, space;
    std::thread thread;
  };
  void run(Worker& w);
  /// Waits until worker `w` may start a scan (see the admission rule above); false when stopping.
  bool admit(const Worker& w);
  void release();
  struct Admitted {
    OdometryRunAhead& owner;
    ~Admitted() { owner.release(); }
  };
  /// The team's thread waits for `robot`'s next result (0: it is busy again).
  void teamWaitsFor(char robot);

  std::map<char, std::unique_ptr<Worker>> workers_;
  std::atomic<bool> stop_{false};
  unsigned cores_;
  std::mutex admit_mutex_;
  std::condition_variable admitted_;
  unsigned running_ = 0;  ///< workers inside a scan
  char awaited_ = 0;      ///< the robot the team's thread waits for; 0 while it is busy
};

}  // namespace cosmo::frontend
