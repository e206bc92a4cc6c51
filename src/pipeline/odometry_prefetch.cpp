#include "cosmo/pipeline/odometry_prefetch.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::pipeline {

OdometryPrefetch::OdometryPrefetch(const std::vector<char>& robots, const LoamParams& params) {
  for (char r : robots) workers_[r] = std::make_unique<Worker>(params);
  for (auto& [r, w] : workers_) {
    Worker* worker = w.get();
    worker->thread = std::thread([worker] { run(*worker); });
  }
}

OdometryPrefetch::~OdometryPrefetch() {
  for (auto& [r, w] : workers_) {
    {
      std::lock_guard<std::mutex> lock(w->mutex);
      w->stop = true;
    }
    w->wake.notify_one();
  }
  for (auto& [r, w] : workers_) w->thread.join();
}

std::future<OdometryResult> OdometryPrefetch::submit(char robot, std::shared_ptr<const Scan> scan) {
  auto it = workers_.find(robot);
  if (it == workers_.end()) throw std::invalid_argument(std::string("odometry prefetch: unknown robot '") + robot + "'");
  Worker& w = *it->second;
  Job job;
  job.scan = std::move(scan);
  std::future<OdometryResult> f = job.result.get_future();
  {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.jobs.push_back(std::move(job));
  }
  w.wake.notify_one();
  return f;
}

void OdometryPrefetch::run(Worker& w) {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(w.mutex);
      w.wake.wait(lock, [&] { return w.stop || !w.jobs.empty(); });
      if (w.jobs.empty()) return;  // stop requested and nothing left
      job = std::move(w.jobs.front());
      w.jobs.pop_front();
    }
    try {
      job.result.set_value(w.odometry.update(*job.scan));
    } catch (...) {
      job.result.set_exception(std::current_exception());
    }
  }
}

}  // namespace cosmo::pipeline
