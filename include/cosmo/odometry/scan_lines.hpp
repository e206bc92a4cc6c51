#pragma once
// A scan organised into scan lines (one per laser), each ordered by azimuth: the structure LOAM's curvature
// needs. Lines come from the `ring` field when present; otherwise from the point order when the cloud is an
// ordered sweep (KITTI .bin: ring after ring, each by azimuth); otherwise from the elevation angle, with the
// beam count estimated from the elevation histogram (unordered / re-ordered / downsampled clouds).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/odometry/loam_params.hpp"

namespace cosmo::odometry {

struct ScanLine {
  std::vector<Eigen::Vector3f> points;  ///< sensor frame, ordered by azimuth
  std::vector<float> time;              ///< per-point time (s, relative to the scan stamp) or empty
  /// 1 where the azimuth gap to the previous point is much larger than the line's typical step (dropped
  /// returns): a line end for the curvature. Same size as `points`.
  std::vector<std::uint8_t> break_before;
};

struct ScanLines {
  std::vector<ScanLine> lines;
  std::string method;  ///< "ring", "order" or "elevation"
  std::size_t numPoints() const;
};

/// Fast atan2 approximation (|error| < 2e-5 rad), radians in (-pi, pi].
float fastAtan2(float y, float x);

/// Organises the valid points of `scan` (finite, range in [min_range, max_range]) into scan lines.
ScanLines organizeScanLines(const Scan& scan, const LoamParams& params);

/// Beam elevation centres (radians, ascending) estimated from a histogram of point elevations; empty when no
/// clear beam structure is found (then the caller splits the elevation range into equal bins).
std::vector<float> estimateBeamElevations(const std::vector<float>& elevations);

}  // namespace cosmo::odometry
