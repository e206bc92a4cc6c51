#pragma once
// Registration features (GlobalRegistration::prepare) of kept keyframe scans, computed once per KeptScan.
// One cache may serve several RobotFrontends of one process that share their registration parameters (TeamRun):
// a delivered scan is then the sender's own KeptScan, so its features are the sender's, bit for bit, and are
// computed once for the team instead of once per robot that registers against it. A copied scan (a decompressed
// payload) is another KeptScan and gets its own entry, so sharing never changes a result.
// With a SpillFile, computed features are written to it and stay in memory only while a registration uses them
// (read back, the same floats, when asked again); without one the cache holds them.
// Thread-safe (RegistrationPool): the first caller computes an entry outside the lock, later callers of the same
// scan wait for it.
#include <cstddef>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>

#include "cosmo/common/scan.hpp"
#include "cosmo/frontend/kept_scan.hpp"
#include "cosmo/frontend/spill_file.hpp"
#include "cosmo/registration/feature_cloud.hpp"

namespace cosmo::frontend {

/// What a FeatureCache holds (benchmarks, tests).
struct FeatureCacheFootprint {
  std::size_t entries = 0;
  std::size_t bytes_in_memory = 0;  ///< features (points, normals, keypoints, FPFH) held or in use
  std::size_t bytes_spilled = 0;    ///< features written to the spill file
};

/// Bytes of a FeatureCloud's arrays.
std::size_t featureCloudBytes(const registration::FeatureCloud& f);

class FeatureCache {
 public:
  using Prepare = std::function<registration::FeatureCloud(const Scan&)>;
  /// `spill`: where computed features go (nullptr: kept in memory).
  explicit FeatureCache(std::shared_ptr<SpillFile> spill = nullptr) : spill_(std::move(spill)) {}

  /// The features of `scan`, computed with `prepare` on the first request (the entry keeps the KeptScan, not its
  /// points). An exception of `prepare` is rethrown to every caller of that scan.
  std::shared_ptr<const registration::FeatureCloud> get(const std::shared_ptr<const KeptScan>& scan,
                                                        const Prepare& prepare);
  std::size_t size() const;
  FeatureCacheFootprint footprint() const;

 private:
  struct Entry {
    std::shared_ptr<const KeptScan> scan;
    std::shared_future<std::shared_ptr<const registration::FeatureCloud>>
        computing;                                           ///< until spilled (or held, or failed)
    std::shared_ptr<const registration::FeatureCloud> held;  ///< without a spill file
    bool spilled = false;
    SpillFile::Extent extent;
    std::weak_ptr<const registration::FeatureCloud> in_use;
  };
  std::shared_ptr<const registration::FeatureCloud> load(const Entry& e) const;

  std::shared_ptr<SpillFile> spill_;
  mutable std::mutex mutex_;
  std::map<const KeptScan*, Entry> entries_;
};

/// FeatureCloud <-> bytes (the spill file's block), exact.
std::vector<char> serializeFeatureCloud(const registration::FeatureCloud& f);
registration::FeatureCloud deserializeFeatureCloud(const std::vector<char>& bytes);

}  // namespace cosmo::frontend
