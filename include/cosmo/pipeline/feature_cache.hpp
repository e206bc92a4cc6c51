#pragma once
// Registration features (GlobalRegistration::prepare) of stored keyframe scans, computed once per Scan object.
// One cache may serve several RobotFrontends of one process that share their registration parameters (TeamRun):
// a delivered scan is then the sender's own Scan object, so its features are the sender's, bit for bit, and are
// computed once for the team instead of once per robot that registers against it. A copied scan (a decompressed
// payload) is another object and gets its own entry, so sharing never changes a result.
// Thread-safe (RegistrationPool): the first caller computes an entry outside the lock, later callers of the same
// scan wait for it; a returned reference stays valid as long as the cache.
#include <cstddef>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "cosmo/common/scan.hpp"
#include "cosmo/registration/feature_cloud.hpp"

namespace cosmo::pipeline {

class FeatureCache {
 public:
  using Prepare = std::function<FeatureCloud(const Scan&)>;
  /// The features of `scan`, computed with `prepare` on the first request (the entry keeps the scan alive).
  /// An exception of `prepare` is rethrown to every caller of that scan.
  const FeatureCloud& get(const std::shared_ptr<const Scan>& scan, const Prepare& prepare);
  std::size_t size() const;

 private:
  struct Entry {
    std::shared_ptr<const Scan> scan;
    std::shared_future<FeatureCloud> features;
  };
  mutable std::mutex mutex_;
  std::map<const Scan*, Entry> entries_;
};

}  // namespace cosmo::pipeline
