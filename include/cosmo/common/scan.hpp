#pragma once
// One LiDAR sweep in the sensor frame, the core's point-cloud type.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "cosmo/common/time.hpp"

namespace cosmo {

struct Scan {
  /// Stamp of the sweep (Ouster/MCD convention: the end of the sweep).
  StampNs stamp = 0;
  /// Points in the sensor frame, metres.
  std::vector<Eigen::Vector3f> points;
  /// Optional per-point fields: each is either empty or the same size as `points`.
  std::vector<float> intensity;
  /// Per-point time relative to `stamp`, seconds (<= 0 for a sweep stamped at its end).
  std::vector<float> time;
  /// Scan line (laser) index; empty when the source has no `ring` field.
  std::vector<std::uint16_t> ring;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool hasTime() const { return !time.empty() && time.size() == points.size(); }
  bool hasRing() const { return !ring.empty() && ring.size() == points.size(); }
  bool hasIntensity() const { return !intensity.empty() && intensity.size() == points.size(); }
  void reserve(std::size_t n) {
    points.reserve(n);
    intensity.reserve(n);
    time.reserve(n);
    ring.reserve(n);
  }
};

/// Copy of `scan` without points that are NaN/Inf or closer than `min_range` (m); keeps the optional fields.
Scan removeInvalidPoints(const Scan& scan, float min_range = 0.0f);

}  // namespace cosmo
