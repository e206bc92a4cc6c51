#pragma once
// A keyframe scan a front-end keeps (its own keyframes and the teammates' it received) for the place recognition of
// scans to come and the registration of loop closures. With a SpillFile its arrays live in the file and in memory
// only while something uses them: get() returns the object in use when there is one, else reads the arrays back,
// the same floats, so whatever is computed from them is the same bit for bit. Without a spill file it holds the
// scan. One KeptScan is one identity: the FeatureCache keys its entries by it, and TeamRun hands the sender's
// KeptScan to the receivers, so the team keeps each scan (and its features) once. Thread-safe.
#include <cstddef>
#include <memory>
#include <mutex>

#include "cosmo/common/scan.hpp"
#include "cosmo/frontend/spill_file.hpp"

namespace cosmo::frontend {

class KeptScan {
 public:
  /// Keeps `scan` (not null): written to `spill` when given (the object is then released by the KeptScan, and
  /// stays in memory as long as its other holders keep it), else held.
  KeptScan(std::shared_ptr<const Scan> scan, std::shared_ptr<SpillFile> spill);

  /// The scan: the object in use, or read back from the spill file.
  std::shared_ptr<const Scan> get() const;
  StampNs stamp() const { return stamp_; }
  std::size_t size() const { return points_; }
  bool spilled() const { return spill_ != nullptr; }
  /// Bytes of the scan's arrays (in the spill file, or in memory when held).
  std::size_t bytes() const { return bytes_; }
  /// Bytes of the scan held in memory now (held, or in use by someone).
  std::size_t bytesInMemory() const;

 private:
  StampNs stamp_ = 0;
  std::size_t points_ = 0;
  std::size_t bytes_ = 0;
  std::shared_ptr<const Scan> held_;
  std::shared_ptr<SpillFile> spill_;
  SpillFile::Extent extent_;
  mutable std::mutex mutex_;
  mutable std::weak_ptr<const Scan> in_use_;
};

/// Bytes of a scan's arrays (points, intensity, time, ring).
std::size_t scanBytes(const Scan& scan);

}  // namespace cosmo::frontend
