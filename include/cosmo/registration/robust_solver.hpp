#pragma once
// Robust rigid transform from (pruned) correspondences, TEASER++ / KISS-Matcher style:
//  * rotation by GNC-TLS (graduated non-convexity over a truncated least-squares cost, Yang et al. 2020) on
//    translation-invariant measurements (differences of correspondence pairs), each GNC step a weighted
//    Procrustes (SVD);
//  * translation by exact per-axis truncated least squares (adaptive voting over the interval endpoints).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace cosmo::registration {

struct GncParams {
  double noise_bound = 0.1;  ///< residual bound c of the TLS cost (m)
  double factor = 1.4;       ///< mu growth per iteration
  int max_iterations = 100;
  double cost_tolerance = 1e-6;
};

struct RotationEstimate {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  std::vector<bool> inliers;  ///< per measurement, final GNC weight > 0.5
  int iterations = 0;
};

/// Weighted Procrustes rotation: argmin_R sum w_i |b_i - R a_i|^2 (proper rotation, det = +1).
Eigen::Matrix3d weightedProcrustes(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                                   const std::vector<double>& w);

/// GNC-TLS rotation with b_i ~ R a_i, |residual| <= params.noise_bound for inliers.
RotationEstimate gncTlsRotation(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                                const GncParams& params);

struct TranslationEstimate {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  std::vector<bool> inliers;  ///< per measurement, inlier on all three axes
};

/// Per-axis TLS: minimise sum_i min((t - v_i)^2, c^2) exactly on each axis.
TranslationEstimate tlsTranslation(const std::vector<Eigen::Vector3d>& v, double noise_bound);

struct RigidEstimate {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();  ///< maps source into target
  std::vector<int> inliers;  ///< indices (into the given pairs) with |t_i - T s_i| <= noise_bound
  bool ok = false;
};

/// Full robust solve on corresponding points (target_i ~ T source_i). Rotation measurements are the
/// differences of pairs (i, i+k), k = 1, 2, ..., until `max_pairs` (all pairs when they fit).
RigidEstimate solveRobustRigid(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                               const GncParams& params, std::size_t max_pairs);

}  // namespace cosmo::registration
