#pragma once
// Hook for tools and benchmarks that time the registration stages: the core calls stageDone(name) at the end
// of each stage and never reads a clock itself.
#include <string>

namespace cosmo::registration {

class StageObserver {
 public:
  virtual ~StageObserver() = default;
  /// Called when the stage `name` has finished (names: downsample, neighbours, normals, spfh, fpfh, matching,
  /// pruning, solve, refine, gate; PCL's feature backend reports normals and fpfh only).
  virtual void stageDone(const std::string& name) = 0;
};

inline void notifyStage(StageObserver* observer, const char* name) {
  if (observer) observer->stageDone(name);
}

}  // namespace cosmo::registration
