#include "cosmo/frontend/registration_pool.hpp"

#include <time.h>

#include <algorithm>
#include <exception>
#include <numeric>
#include <optional>

namespace cosmo::frontend {

namespace {
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

RegistrationPool::RegistrationPool(unsigned threads) {
  cpu_.assign(threads, 0.0);
  for (unsigned i = 0; i < threads; ++i) threads_.emplace_back([this, i] { run(i); });
}

RegistrationPool::~RegistrationPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

std::shared_future<registration::RegistrationResult> RegistrationPool::submit(Job job) {
  Queued q{std::move(job), {}};
  std::shared_future<registration::RegistrationResult> f = q.result.get_future().share();
  if (threads_.empty()) {  // zero threads: inline
    try {
      q.result.set_value(q.job());
    } catch (...) { q.result.set_exception(std::current_exception()); }
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    return f;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(q));
  }
  wake_.notify_one();
  return f;
}

std::size_t RegistrationPool::jobsDone() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return done_;
}

double RegistrationPool::cpuSeconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::accumulate(cpu_.begin(), cpu_.end(), 0.0);
}

void RegistrationPool::run(std::size_t slot) {
  for (;;) {
    Queued q;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      q = std::move(queue_.front());
      queue_.pop_front();
    }
    std::optional<registration::RegistrationResult> result;
    std::exception_ptr error;
    try {
      result = q.job();
    } catch (...) { error = std::current_exception(); }
    {  // counted before the result is seen, so a caller holding the result sees the job counted
      const double cpu = threadCpuSeconds();
      std::lock_guard<std::mutex> lock(mutex_);
      cpu_[slot] = cpu;
      ++done_;
    }
    if (error) {
      q.result.set_exception(error);
    } else {
      q.result.set_value(std::move(*result));
    }
  }
}

}  // namespace cosmo::frontend
