#include "cosmo/frontend/odometry_run_ahead.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cosmo::frontend {

OdometryRunAhead::OdometryRunAhead(std::map<char, std::unique_ptr<sequence::ScanSource>> sources, const sequence::SequenceTiming& timing,
                                   const FrontendParams& params, const std::map<char, Trajectory>& references,
                                   unsigned cores)
    : cores_(cores > 0 ? cores : std::max(1u, std::thread::hardware_concurrency())) {
  for (auto& [robot, source] : sources) {
    std::map<char, std::unique_ptr<sequence::ScanSource>> one;
    one[robot] = std::move(source);
    auto ref = references.find(robot);
    workers_[robot] = std::make_unique<Worker>(robot, sequence::MergedScanStream(std::move(one), timing), params,
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
  {
    std::lock_guard<std::mutex> lock(admit_mutex_);
    admitted_.notify_all();
  }
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
    for (;;) {
      if (!admit(w)) break;
      AheadScan a;
      bool more = false;
      {
        const Admitted admitted{*this};  // released at the end of the scan's work, also on an exception
        more = w.stream.next(robot, scan);
        if (more) {
          a.robot = robot;
          a.stamp = scan.stamp;
          a.odometry = w.odometry.update(scan);
          if (w.taker.update(scan.stamp, a.odometry.pose).is_keyframe)
            a.keyframe_scan = std::make_shared<const Scan>(w.taker.keyframeScan(scan, w.reference));
        }
      }
      if (!more) break;
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

bool OdometryRunAhead::admit(const Worker& w) {
  std::unique_lock<std::mutex> lock(admit_mutex_);
  admitted_.wait(lock, [&] { return stop_ || awaited_ == w.robot || running_ + (awaited_ ? 0u : 1u) < cores_; });
  if (stop_) return false;
  ++running_;
  return true;
}

void OdometryRunAhead::release() {
  std::lock_guard<std::mutex> lock(admit_mutex_);
  --running_;
  admitted_.notify_all();
}

void OdometryRunAhead::teamWaitsFor(char robot) {
  std::lock_guard<std::mutex> lock(admit_mutex_);
  awaited_ = robot;
  admitted_.notify_all();
}

bool OdometryRunAhead::next(AheadScan& out) {
  Worker* best = nullptr;
  StampNs best_stamp = 0;
  for (auto& [robot, w] : workers_) {  // robot id order: ties go to the lower id, as in MergedScanStream
    std::unique_lock<std::mutex> lock(w->mutex);
    if (w->results.empty() && !w->done) {
      lock.unlock();
      teamWaitsFor(robot);
      lock.lock();
      w->ready.wait(lock, [&] { return !w->results.empty() || w->done; });
      lock.unlock();
      teamWaitsFor(0);
      lock.lock();
    }
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

}  // namespace cosmo::frontend
