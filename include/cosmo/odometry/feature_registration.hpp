#pragma once
// Scan-to-local-map registration of LOAM features: deskew the features with a given motion (the caller
// iterates: prediction, then the estimate), then iterate {associate features with map lines / planes, robust
// Gauss-Newton steps}, coarse (feature subsample) to fine; Huber weights on the distances;
// directions the constraints do not determine (e.g. along a featureless corridor) keep the initial guess
// (Zhang, Kaess & Singh 2016 "solution remapping").
#include <optional>

#include "cosmo/common/pose.hpp"
#include "cosmo/odometry/feature_correspondences.hpp"
#include "cosmo/odometry/feature_extraction.hpp"
#include "cosmo/odometry/local_feature_map.hpp"
#include "cosmo/odometry/loam_params.hpp"

namespace cosmo::odometry {

struct FeatureRegistrationResult {
  Pose3 pose = Pose3::Identity();  ///< sensor pose at the scan stamp in the map (odometry) frame
  int iterations = 0;
  bool converged = false;
  std::size_t num_edge_constraints = 0;
  std::size_t num_plane_constraints = 0;
  int degenerate_directions = 0;  ///< directions of [rot, trans] left at the guess
  double inlier_fraction = 0.0;   ///< features with a constraint and |r| < inlier_dist, over all features
  /// The last association (all features, sensor-frame points as deskewed for it): reused by
  /// refineRedeskewed when only the deskew of the features changes.
  std::vector<FeatureConstraint> constraints;
  /// Rotation from the sweep's start to the stamp when it was estimated with the pose
  /// (refineContinuousRotation): the features were deskewed with it, and so should the map's copy be.
  std::optional<Eigen::Matrix3d> sweep_rotation;
};

/// Motion used for deskewing the features before registration: the sensor motion over `period` seconds
/// ending at the scan stamp (see deskewConstantVelocity).
struct DeskewReference {
  Pose3 delta = Pose3::Identity();
  double period = 0.0;  ///< s
};

/// The edge and planar feature points of `features` deskewed with constant velocity `delta` over `period`
/// (deskewConstantVelocity on both sets).
void deskewFeatures(const LoamFeatures& features, const Pose3& delta, double period,
                    std::vector<Eigen::Vector3d>& edges, std::vector<Eigen::Vector3d>& planes);

/// One robust Gauss-Newton step for the constraints at pose T; returns the update [rot, trans] as a perturbation
/// about the sensor position (apply with applyCentredUpdate) and the number of degenerate directions through
/// `degenerate`. (About the sensor position, not the odometry origin: far from the origin rotation and
/// translation would mix, and the degeneracy test would depend on the distance travelled.)
Vector6 robustGaussNewtonStep(const std::vector<FeatureConstraint>& constraints, const Pose3& T, double huber_delta,
                              double min_eigenvalue_per_constraint, int& degenerate);

/// Constraints with |residual| < inlier_dist at pose T, over num_features (0 when there are no features).
double inlierFraction(const std::vector<FeatureConstraint>& constraints, const Pose3& T, double inlier_dist,
                      std::size_t num_features);

/// T <- C exp(dx) C^-1 T with C the translation to T's position.
Pose3 applyCentredUpdate(const Vector6& dx, const Pose3& T);

/// Registers `features` (sensor frame) to `map` starting at `guess`.
FeatureRegistrationResult registerFeatures(const LoamFeatures& features, const LocalFeatureMap& map, const Pose3& guess,
                                           const LoamParams& params, const std::optional<DeskewReference>& deskew);

/// Re-registration after the features were deskewed again with a corrected motion `deskew`: the map is the
/// same and each feature moved by at most the deskew change (centimetres), so `previous`' lines and planes are
/// kept (each constraint's point re-deskewed, no k-NN search or fit) and up to `max_steps` robust Gauss-Newton
/// steps start from previous.pose. The edge constraints keep their normal (first order in the point's shift).
FeatureRegistrationResult refineRedeskewed(const LoamFeatures& features, FeatureRegistrationResult previous,
                                           const LoamParams& params, const DeskewReference& deskew, int max_steps);

/// Fraction of (every `stride`-th) features that find a map constraint with |r| < inlier_dist at pose T.
double scorePose(const LoamFeatures& features, const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                 std::size_t stride);

}  // namespace cosmo::odometry
