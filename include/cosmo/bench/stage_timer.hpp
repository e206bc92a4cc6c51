#pragma once
// Timing StageObserver for tools and benchmarks only (the core never reads the clock): accumulates the time
// between consecutive stageDone() calls per stage name. It measures the calling thread's CPU time
// (CLOCK_THREAD_CPUTIME_ID; the registration is single-threaded), so figures taken on a loaded machine stay
// close to idle-machine wall time; wallMs() gives the wall-clock total as well.
#include <ctime>
#include <map>
#include <string>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/registration/stage_observer.hpp"

namespace cosmo::bench {

class StageTimer : public registration::StageObserver {
 public:
  void restart() {
    ms_.clear();
    watch_.restart();
    last_ = cpuMs();
  }
  void stageDone(const std::string& name) override {
    const double now = cpuMs();
    ms_[name] += now - last_;
    last_ = now;
  }
  double wallMs() const { return watch_.elapsedMs(); }
  static double cpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
  }
  const std::map<std::string, double>& milliseconds() const { return ms_; }
  double total() const {
    double t = 0.0;
    for (const auto& [k, v] : ms_) t += v;
    return t;
  }

 private:
  bench::Stopwatch watch_;
  double last_ = 0.0;
  std::map<std::string, double> ms_;
};

/// Stage names in pipeline order.
inline const char* const kRegistrationStages[] = {"downsample", "neighbours", "normals", "spfh",   "fpfh",
                                                  "matching",   "pruning",    "solve",   "refine", "gate"};

}  // namespace cosmo::bench
