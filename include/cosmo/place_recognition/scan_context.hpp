#pragma once
// The ScanContext descriptor (Kim & Kim, IROS 2018): a polar bird's-eye grid of the scan around the sensor,
// `rings` radial bins of max_range / rings metres times `sectors` azimuth bins of 2*pi / sectors, each bin
// holding the maximum point height in it; plus the rotation-invariant ring key and the sector key.
//
// Height reference: a bin's value is max(0, z + sensor_height) over the points in the bin, with z the point's
// height in the sensor frame (the scan handed in is a dewarped keyframe scan in the sensor frame, z up) and
// sensor_height a configurable offset (default 2 m, roughly the height of a vehicle-mounted LiDAR above the
// ground) so that ground-level bins are positive. A bin with no point, or whose highest point lies more than
// sensor_height below the sensor, holds 0 and counts as empty.
//
// Layout: descriptor(r, s) with ring r = floor(range / (max_range / rings)) (range = sqrt(x^2 + y^2)) and
// sector s = floor(azimuth / (2*pi / sectors)), azimuth = atan2(y, x) in [0, 2*pi), counter-clockwise from +x.
#include <Eigen/Core>

#include "cosmo/common/config.hpp"
#include "cosmo/common/scan.hpp"

namespace cosmo::place_recognition {

/// How column pairs with an empty column enter the descriptor distance (an empty column has no occupied bin).
enum class EmptyColumnPolicy {
  /// A pair with one empty column counts as cosine distance 1; a pair of two empty columns is left out of the
  /// average. Penalises occupancy that one scan sees and the other does not.
  kPenalizeOneSided,
  /// Only pairs where both columns are occupied enter the average (Kim's reference implementation).
  kSkipIfEitherEmpty,
};

struct ScanContextParams {
  int rings = 20;              ///< radial bins (paper: 20)
  int sectors = 60;            ///< azimuth bins (paper: 60, 6 degrees each)
  double max_range = 80.0;     ///< m, points farther (in the x-y plane) are ignored (paper: 80 m)
  double min_range = 0.0;      ///< m, points closer (x-y plane) are ignored, e.g. hits on the robot itself
  double sensor_height = 2.0;  ///< m, added to the sensor-frame z so that ground bins are positive
  /// Downsampling before binning: only every point_stride-th point is used (1 = all points). A bin keeps
  /// the maximum height, so thinning dense scans changes few bins (measured in bench_scancontext).
  int point_stride = 1;
  EmptyColumnPolicy empty_columns = EmptyColumnPolicy::kPenalizeOneSided;
  /// Column-shift search: -1 = all `sectors` shifts (exact); r >= 0 = align the sector keys first and search
  /// only the shifts within +-r of that alignment (faster, may miss the best shift).
  int coarse_search_radius = -1;

  /// Reads the `scan_context` section (or the keys directly) of config/place_recognition.yaml.
  static ScanContextParams fromConfig(const ConfigNode& node);
  /// Throws std::invalid_argument naming the field when a value is out of range.
  void validate() const;

  /// The YAML keys, one per member (common/param_list.hpp); `empty_columns` (an enumeration) is read by fromConfig.
  template <class Visitor>
  void visit(Visitor&& v) {
    v("rings", rings);
    v("sectors", sectors);
    v("max_range", max_range);
    v("min_range", min_range);
    v("sensor_height", sensor_height);
    v("point_stride", point_stride);
    v("coarse_search_radius", coarse_search_radius);
  }
};

struct ScanContext {
  Eigen::MatrixXf descriptor;  ///< rings x sectors, bin = max height above the reference (0 = empty)
  Eigen::VectorXf ring_key;    ///< per ring: fraction of occupied sectors (rotation invariant)
  Eigen::VectorXf sector_key;  ///< per sector: mean bin value over the rings (shifts with rotation)
};

/// Descriptor of a scan in its sensor frame; non-finite points are skipped; an empty scan gives all zeros.
ScanContext makeScanContext(const Scan& scan, const ScanContextParams& p);

/// Result of comparing two descriptors.
struct DescriptorMatch {
  double distance = 1.0;  ///< mean column-wise cosine distance at the best shift, in [0, 1] (1 = nothing shared)
  int shift = 0;          ///< best column shift: candidate column = (query column + shift) mod sectors
  /// Yaw estimate, radians in (-pi, pi]: shift * 2*pi / sectors, wrapped. Sign convention: it is the yaw of the
  /// query sensor frame relative to the candidate sensor frame, i.e. the yaw of T_candidate_query, so that a
  /// point p in the query frame is at about Rz(yaw) * p in the candidate frame (the initial guess for
  /// registering the query scan onto the candidate scan). A query scan that is the candidate scan turned by
  /// -psi (its sensor turned by +psi) gives yaw = +psi.
  double yaw = 0.0;
};

/// Distance between two descriptors of the same size (throws std::invalid_argument otherwise): for each column
/// shift the mean cosine distance 1 - <q_j, c_{j+shift}> / (|q_j| |c_{j+shift}|) over the column pairs, empty
/// columns as given by `empty_columns`, minimised over the shifts. Pairs of all-empty descriptors give 1.
DescriptorMatch scanContextDistance(const ScanContext& query, const ScanContext& candidate,
                                    EmptyColumnPolicy empty_columns, int coarse_search_radius = -1);
/// Same with the defaults (one-sided empty columns penalised, all shifts).
DescriptorMatch scanContextDistance(const ScanContext& query, const ScanContext& candidate);

/// Column shift that best aligns the sector keys (minimum L1 difference), the coarse step of the search.
int sectorKeyShift(const ScanContext& query, const ScanContext& candidate);

}  // namespace cosmo::place_recognition
