#pragma once
// Correspondences of LOAM features with the local map, as linear constraints r = n . (T p) - d:
// - edge point -> line through its nearest map edge points (point-to-line distance; n points from the line to
//   the transformed point, so r is the distance and its gradient is exact at the current estimate);
// - planar point -> plane through its nearest map planar points (point-to-plane distance).
// The fit rules (neighbour count and distance, line condition number, mean plane residual) are spec 4.1's.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/odometry/local_feature_map.hpp"
#include "cosmo/odometry/loam_params.hpp"

namespace cosmo::odometry {

struct FeatureConstraint {
  Eigen::Vector3d point;   ///< feature in the sensor frame
  Eigen::Vector3d normal;  ///< unit normal in the odometry frame
  double offset = 0.0;     ///< r = normal . (T * point) - offset
  bool edge = false;
  std::size_t feature = 0;  ///< index in the edge (edge) or planar feature list
};

struct LinearConstraint {
  Eigen::Vector3d normal;
  double offset = 0.0;
};

/// Line through `neighbours` (>= min_line_fit_points, largest / middle eigenvalue >= the condition number),
/// as the constraint "distance of q to the line". nullopt when the fit is rejected.
std::optional<LinearConstraint> fitLineConstraint(const std::vector<Eigen::Vector3d>& neighbours,
                                                  const Eigen::Vector3d& q, const LoamParams& params);
/// Plane through `neighbours` (>= min_plane_fit_points, mean |distance| <= max_avg_point_plane_dist).
std::optional<LinearConstraint> fitPlaneConstraint(const std::vector<Eigen::Vector3d>& neighbours,
                                                   const LoamParams& params);

/// Line fitted to map edge points: the constraint for a query q is the distance of q to it.
struct MapLine {
  Eigen::Vector3d mean;               ///< centroid of the neighbours
  Eigen::Vector3d direction;          ///< unit, largest eigenvector of their scatter
  Eigen::Vector3d normal_if_on_line;  ///< unit, perpendicular to direction (used when q lies on the line)
};
/// The line through `neighbours` under the fit rules of fitLineConstraint (nullopt when rejected).
std::optional<MapLine> fitMapLine(const std::vector<Eigen::Vector3d>& neighbours, const LoamParams& params);
/// The constraint "distance of q to `line`" (n from the line to q; offset n . mean).
LinearConstraint lineConstraint(const MapLine& line, const Eigen::Vector3d& q);

/// What the last association of each feature found, so that the next association of the same feature can
/// skip the k-NN search and the fit while its query point stays within `reuse_radius` of the last one: a
/// radius below which the set of neighbours provably cannot change (half the gap between the k-th and the
/// (k+1)-th neighbour distance, and the margins to the maximum neighbour distance). The constraint is then
/// the same as a new search and fit would give, up to the summation order of the fit (last-bit differences).
struct AssociationMemory {
  struct Entry {
    Eigen::Vector3d query = Eigen::Vector3d::Zero();  ///< map-frame query point of the last search
    double reuse_radius = -1.0;                       ///< (m); < 0: nothing remembered
    bool fitted = false;                              ///< the fit was accepted
    Eigen::Vector3d a = Eigen::Vector3d::Zero();      ///< line: mean; plane: normal
    Eigen::Vector3d b = Eigen::Vector3d::Zero();      ///< line: direction
    Eigen::Vector3d c = Eigen::Vector3d::Zero();      ///< line: normal_if_on_line
    double offset = 0.0;                              ///< plane offset
  };
  std::vector<Entry> edges, planes;  ///< by feature index in the full (not subsampled) lists
  /// Forgets everything and sizes the memory for the given feature counts.
  void reset(std::size_t num_edges, std::size_t num_planes);
  std::size_t reused = 0, searched = 0;  ///< statistics: associations answered from memory / by a search
};

/// associateFeatures (stride 1) with a memory: feature i of the given lists is feature i * memory_stride of
/// the memory (the lists may be subsamples); `remember`: store new searches (costs a (k+1)-th neighbour).
void associateFeaturesRemembering(const std::vector<Eigen::Vector3d>& edges, const std::vector<Eigen::Vector3d>& planes,
                                  const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                                  std::vector<FeatureConstraint>& out, AssociationMemory& memory,
                                  std::size_t memory_stride, bool remember);

/// Constraints for the features (sensor frame) at the pose `T`; every `stride`-th feature only.
void associateFeatures(const std::vector<Eigen::Vector3d>& edges, const std::vector<Eigen::Vector3d>& planes,
                       const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                       std::vector<FeatureConstraint>& out, std::size_t stride = 1);

}  // namespace cosmo::odometry
