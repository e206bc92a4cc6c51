#include "cosmo/pipeline/odometry_run_ahead.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::pipeline {

OdometryRunAhead::OdometryRunAhead(std::map<char, std::unique_ptr<ScanSource>> sources, const SequenceTiming& timing,
                                   const LoamParams& params) {
  for (auto& [robot, source] : sources) {
    std::map<char, std::unique_ptr<ScanSource>> one;
    one[robot] = std::move(source);
    workers_[robot] = std::make_unique<Worker>(MergedScanStream(std::move(one), timing), params);
  }
  for (auto& [robot, w] : workers_) {
    Worker* worker = w.get();
    worker->thread = std::thread([this, worker] { run(*worker); });
  }
}

OdometryRunAhead::~OdometryRunAhead() {
  stop_ = true;
  for (auto& [robot, w] : workers_) w->thread.join();
}

void OdometryRunAhead::run(Worker& w) {
  try {
    char robot;
    Scan scan;
    while (!stop_ && w.stream.next(robot, scan)) {
      Computed c{scan.stamp, w.odometry.update(scan)};
      std::lock_guard<std::mutex> lock(w.mutex);
      w.results.push_back(std::move(c));
      w.ready.notify_one();
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.error = std::current_exception();
  }
  std::lock_guard<std::mutex> lock(w.mutex);
  w.done = true;
  w.ready.notify_one();
}

OdometryResult OdometryRunAhead::next(char robot, StampNs stamp) {
  auto it = workers_.find(robot);
  if (it == workers_.end())
    throw std::invalid_argument(std::string("odometry run-ahead: unknown robot '") + robot + "'");
  Worker& w = *it->second;
  std::unique_lock<std::mutex> lock(w.mutex);
  w.ready.wait(lock, [&] { return !w.results.empty() || w.done; });
  if (w.results.empty()) {
    if (w.error) std::rethrow_exception(w.error);
    throw std::logic_error(std::string("odometry run-ahead: robot ") + robot + " has no scan left for stamp " +
                           std::to_string(stamp));
  }
  Computed c = std::move(w.results.front());
  w.results.pop_front();
  if (c.stamp != stamp)
    throw std::logic_error(std::string("odometry run-ahead: robot ") + robot + "'s reader gave the scan at " +
                           std::to_string(c.stamp) + " where the team's stream has " + std::to_string(stamp));
  return std::move(c.result);
}

}  // namespace cosmo::pipeline
