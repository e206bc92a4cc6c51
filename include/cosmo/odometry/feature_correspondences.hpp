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

namespace cosmo {

struct FeatureConstraint {
  Eigen::Vector3d point;   ///< feature in the sensor frame
  Eigen::Vector3d normal;  ///< unit normal in the odometry frame
  double offset = 0.0;     ///< r = normal . (T * point) - offset
  bool edge = false;
  std::size_t feature = 0;      ///< index in the edge (edge) or planar feature list
  double jacobian_scale = 1.0;  ///< d(point in map)/d(pose): 1 + t/period for points deskewed with the estimate
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

/// Constraints for the features (sensor frame) at the pose `T`; every `stride`-th feature only.
void associateFeatures(const std::vector<Eigen::Vector3d>& edges, const std::vector<Eigen::Vector3d>& planes,
                       const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                       std::vector<FeatureConstraint>& out, std::size_t stride = 1);

}  // namespace cosmo
