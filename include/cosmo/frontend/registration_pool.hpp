#pragma once
// Threads that run loop-closure registrations (GlobalRegistration jobs) off the team's thread. Jobs run in the
// order they were submitted (FIFO, several at once with several threads); each job is a pure function of its
// scans and parameters, so its result does not depend on which thread ran it or when. The caller consumes the
// results in its own order (TeamRun: submission order), which keeps the output byte-identical to running every
// registration inline. Jobs share a thread-safe FeatureCache (a scan's features are computed once; a job that
// needs features another job is computing waits for them).
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "cosmo/registration/global_registration.hpp"

namespace cosmo::frontend {

class RegistrationPool {
 public:
  using Job = std::function<registration::RegistrationResult()>;
  /// Starts `threads` threads; zero: every job runs inline in submit() (its result is ready when submit returns).
  explicit RegistrationPool(unsigned threads);
  /// Stops the threads after their current job; jobs not started are abandoned (their futures report a broken
  /// promise).
  ~RegistrationPool();
  RegistrationPool(const RegistrationPool&) = delete;
  RegistrationPool& operator=(const RegistrationPool&) = delete;

  /// Queues `job`; its result (or exception) arrives in the returned future.
  std::shared_future<registration::RegistrationResult> submit(Job job);
  unsigned threads() const { return static_cast<unsigned>(threads_.size()); }
  /// Jobs finished so far.
  std::size_t jobsDone() const;
  /// CPU seconds the pool's threads spent so far (updated after each job).
  double cpuSeconds() const;

 private:
  struct Queued {
    Job job;
    std::promise<registration::RegistrationResult> result;
  };
  void run(std::size_t slot);

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Queued> queue_;
  bool stop_ = false;
  std::size_t done_ = 0;
  std::vector<double> cpu_;  ///< per thread
  std::vector<std::thread> threads_;
};

}  // namespace cosmo::frontend
