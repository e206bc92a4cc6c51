#pragma once
// Trajectory evaluation shared by tools and benchmarks: SE(3) Umeyama alignment (no scale), absolute
// trajectory error, and KITTI-style relative errors over path-length segments.
#include <vector>

#include "cosmo/common/pose.hpp"

namespace cosmo {

/// Rigid transform A minimising sum |A * source_i - target_i|^2 (Umeyama 1991 without scale). Needs >= 3
/// non-collinear points for a unique rotation; fewer points give the best translation-only / partial fit.
Pose3 umeyamaAlignment(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target);

struct AteResult {
  double rmse = 0.0;  ///< m
  double mean = 0.0;
  double max = 0.0;
  Pose3 alignment = Pose3::Identity();  ///< applied to the estimate
};
/// Absolute trajectory error of `estimate` vs `reference` (same length, matching indices) after aligning
/// the estimate's positions to the reference with `umeyamaAlignment`.
AteResult absoluteTrajectoryError(const std::vector<Pose3>& estimate, const std::vector<Pose3>& reference);

struct SegmentError {
  double length = 0.0;              ///< segment length (m)
  std::size_t count = 0;            ///< segments evaluated
  double translation_percent = 0.0; ///< mean |t_err| / length * 100
  double rotation_deg_per_m = 0.0;  ///< mean angle(R_err) / length, degrees per metre
};
/// KITTI devkit style: for every `step`-th start frame and each length L, the first frame at least L metres
/// (reference path length) later; error of the estimated relative pose against the reference one.
std::vector<SegmentError> segmentErrors(const std::vector<Pose3>& estimate, const std::vector<Pose3>& reference,
                                        const std::vector<double>& lengths, std::size_t step = 1);

/// Translation (m) and rotation (rad) of A^-1 * B.
double translationError(const Pose3& a, const Pose3& b);
double rotationErrorRad(const Pose3& a, const Pose3& b);

}  // namespace cosmo
