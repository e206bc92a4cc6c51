#include "cosmo/pipeline/odometry_run_ahead.hpp"

#include <algorithm>

namespace cosmo::pipeline {

OdometryRunAhead::OdometryRunAhead(std::map<char, std::unique_ptr<ScanSource>> sources, const SequenceTiming& timing,
                                   const LoamParams& params, double keyframe_distance, std::size_t max_held_scans)
    : max_held_(std::max<std::size_t>(1, max_held_scans)) {
  for (auto& [robot, source] : sources) {
    std::map<char, std::unique_ptr<ScanSource>> one;
    one[robot] = std::move(source);
    workers_[robot] = std::make_unique<Worker>(MergedScanStream(std::move(one), timing), params, keyframe_distance);
  }
  for (auto& [robot, w] : workers_) {
    Worker* worker = w.get();
    worker->thread = std::thread([this, worker] { run(*worker); });
  }
}

OdometryRunAhead::~OdometryRunAhead() {
  for (auto& [robot, w] : workers_) {
    std::lock_guard<std::mutex> lock(w->mutex);
    w->stop = true;
    w->changed.notify_all();
  }
  for (auto& [robot, w] : workers_) w->thread.join();
}

void OdometryRunAhead::run(Worker& w) {
  try {
    RunAheadScan item;
    Scan scan;
    while (w.stream.next(item.robot, scan)) {
      item.odometry = w.odometry.update(scan);
      item.keyframe = w.keyframer.update(item.odometry.pose).is_keyframe;
      if (item.keyframe) {
        item.scan = std::make_shared<const Scan>(std::move(scan));
      } else {
        auto stamp_only = std::make_shared<Scan>();
        stamp_only->stamp = scan.stamp;
        item.scan = std::move(stamp_only);
      }
      std::unique_lock<std::mutex> lock(w.mutex);
      w.changed.wait(lock, [&] { return w.stop || !item.keyframe || w.held < max_held_; });
      if (w.stop) break;
      w.held += item.keyframe ? 1 : 0;
      w.results.push_back(std::move(item));
      w.changed.notify_all();
      item = RunAheadScan{};
      scan = Scan{};
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.error = std::current_exception();
  }
  std::lock_guard<std::mutex> lock(w.mutex);
  w.done = true;
  w.changed.notify_all();
}

bool OdometryRunAhead::next(RunAheadScan& out) {
  // Every unfinished worker's head is needed to know which stamp comes first.
  Worker* best = nullptr;
  StampNs best_stamp = 0;
  for (auto& [robot, w] : workers_) {  // map order = robot id order: ties go to the lower id
    std::unique_lock<std::mutex> lock(w->mutex);
    w->changed.wait(lock, [&] { return !w->results.empty() || w->done; });
    if (w->results.empty()) {
      if (w->error) std::rethrow_exception(w->error);
      continue;
    }
    const StampNs stamp = w->results.front().scan->stamp;
    if (!best || stamp < best_stamp) {
      best = w.get();
      best_stamp = stamp;
    }
  }
  if (!best) return false;
  std::lock_guard<std::mutex> lock(best->mutex);
  out = std::move(best->results.front());
  best->results.pop_front();
  if (out.keyframe) --best->held;
  best->changed.notify_all();
  return true;
}

std::map<char, std::size_t> OdometryRunAhead::dropped() const {
  std::map<char, std::size_t> all;
  for (const auto& [robot, w] : workers_) {
    std::lock_guard<std::mutex> lock(w->mutex);
    if (!w->done) continue;
    for (const auto& [r, n] : w->stream.dropped()) all[r] += n;
  }
  return all;
}

}  // namespace cosmo::pipeline
