#include "cosmo/pipeline/odometry_run_ahead.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::pipeline {

OdometryRunAhead::OdometryRunAhead(std::map<char, std::unique_ptr<ScanSource>> sources, const SequenceTiming& timing,
                                   const FrontendParams& params, const std::map<char, Trajectory>& references) {
  for (auto& [robot, source] : sources) {
    std::map<char, std::unique_ptr<ScanSource>> one;
    one[robot] = std::move(source);
    auto ref = references.find(robot);
    workers_[robot] = std::make_unique<Worker>(MergedScanStream(std::move(one), timing), params,
                                               ref == references.end() ? Trajectory{} : ref->second);
  }
  for (auto& [robot, w] : workers_) {
    Worker* worker = w.get();
    worker->thread = std::thread([this, worker] { run(*worker); });
  }
}

OdometryRunAhead::~OdometryRunAhead() { stop(); }

void OdometryRunAhead::stop() {
  stop_ = true;
  for (auto& [robot, w] : workers_) {
    {
      std::lock_guard<std::mutex> lock(w->mutex);
      w->space.notify_all();
    }
    if (w->thread.joinable()) w->thread.join();
  }
}

void OdometryRunAhead::run(Worker& w) {
  try {
    char robot;
    Scan scan;
    while (!stop_ && w.stream.next(robot, scan)) {
      AheadScan a;
      a.robot = robot;
      a.stamp = scan.stamp;
      a.odometry = w.odometry.update(scan);
      if (w.taker.update(scan.stamp, a.odometry.pose).is_keyframe)
        a.keyframe_scan = std::make_shared<const Scan>(w.taker.keyframeScan(scan, w.reference));
      std::unique_lock<std::mutex> lock(w.mutex);
      w.space.wait(lock, [&] { return stop_ || w.results.size() < kMaxAhead; });
      w.results.push_back(std::move(a));
      w.ready.notify_one();
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.error = std::current_exception();
  }
  std::lock_guard<std::mutex> lock(w.mutex);
  w.dropped = w.stream.dropped();
  w.done = true;
  w.ready.notify_one();
}

bool OdometryRunAhead::next(AheadScan& out) {
  Worker* best = nullptr;
  StampNs best_stamp = 0;
  for (auto& [robot, w] : workers_) {  // robot id order: ties go to the lower id, as in MergedScanStream
    std::unique_lock<std::mutex> lock(w->mutex);
    w->ready.wait(lock, [&] { return !w->results.empty() || w->done; });
    if (w->results.empty()) {
      if (w->error) std::rethrow_exception(w->error);
      continue;
    }
    if (!best || w->results.front().stamp < best_stamp) {
      best = w.get();
      best_stamp = w->results.front().stamp;
    }
  }
  if (!best) return false;
  std::lock_guard<std::mutex> lock(best->mutex);
  out = std::move(best->results.front());
  best->results.pop_front();
  best->space.notify_one();
  return true;
}

std::map<char, std::size_t> OdometryRunAhead::dropped() {
  std::map<char, std::size_t> all;
  for (auto& [robot, w] : workers_) {
    std::lock_guard<std::mutex> lock(w->mutex);
    for (const auto& [r, n] : w->dropped) all[r] += n;
  }
  return all;
}

}  // namespace cosmo::pipeline
