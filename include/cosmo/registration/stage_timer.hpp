#pragma once
// Wall-clock StageObserver for tools and benchmarks only (the core never reads the clock): accumulates the
// time between consecutive stageDone() calls per stage name.
#include <map>
#include <string>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/registration/stage_observer.hpp"

namespace cosmo {

class StageTimer : public StageObserver {
 public:
  void restart() {
    ms_.clear();
    watch_.restart();
  }
  void stageDone(const std::string& name) override {
    ms_[name] += watch_.elapsedMs();
    watch_.restart();
  }
  const std::map<std::string, double>& milliseconds() const { return ms_; }
  double total() const {
    double t = 0.0;
    for (const auto& [k, v] : ms_) t += v;
    return t;
  }

 private:
  bench::Stopwatch watch_;
  std::map<std::string, double> ms_;
};

/// Stage names in pipeline order.
inline const char* const kRegistrationStages[] = {"downsample", "normals", "fpfh",   "matching",
                                                   "pruning",    "solve",   "refine", "gate"};

}  // namespace cosmo
