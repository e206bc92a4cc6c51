#pragma once
// LOAM odometry run ahead of the team, one worker thread per robot: a robot's odometry depends only on its own
// scans, so the robots' odometry can run in parallel with each other and with the rest of the pipeline (radio,
// place recognition, registration), which stays in one thread and in sequence order. Each worker feeds its robot's
// scans to its own LoamOdometry in submission order, so every result is exactly what RobotFrontend's own
// LoamOdometry would have computed: the output does not depend on the thread count or timing.
#include <condition_variable>
#include <deque>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/odometry/loam_params.hpp"

namespace cosmo::pipeline {

class OdometryPrefetch {
 public:
  OdometryPrefetch(const std::vector<char>& robots, const LoamParams& params);
  ~OdometryPrefetch();
  OdometryPrefetch(const OdometryPrefetch&) = delete;
  OdometryPrefetch& operator=(const OdometryPrefetch&) = delete;

  /// Queues `scan` on `robot`'s worker (after that robot's earlier scans); the future holds its odometry.
  std::future<OdometryResult> submit(char robot, std::shared_ptr<const Scan> scan);

 private:
  struct Job {
    std::shared_ptr<const Scan> scan;
    std::promise<OdometryResult> result;
  };
  struct Worker {
    explicit Worker(const LoamParams& params) : odometry(params) {}
    LoamOdometry odometry;
    std::deque<Job> jobs;
    std::mutex mutex;
    std::condition_variable wake;
    bool stop = false;
    std::thread thread;
  };
  static void run(Worker& w);

  std::map<char, std::unique_ptr<Worker>> workers_;
};

}  // namespace cosmo::pipeline
