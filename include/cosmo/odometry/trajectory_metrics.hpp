#pragma once
// Trajectory evaluation shared by tools and benchmarks: SE(3) Umeyama alignment (no scale), absolute
// trajectory error, and KITTI-style relative errors over path-length segments.
#include <vector>

#include "cosmo/common/pose.hpp"

namespace cosmo::odometry {

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
  double length = 0.0;               ///< segment length (m)
  std::size_t count = 0;             ///< segments evaluated
  double translation_percent = 0.0;  ///< mean |t_err| / length * 100
  double rotation_deg_per_m = 0.0;   ///< mean angle(R_err) / length, degrees per metre
};
/// KITTI devkit style: for every `step`-th start frame and each length L, the first frame at least L metres
/// (reference path length) later; error of the estimated relative pose against the reference one.
std::vector<SegmentError> segmentErrors(const std::vector<Pose3>& estimate, const std::vector<Pose3>& reference,
                                        const std::vector<double>& lengths, std::size_t step = 1);

/// A stretch of a reference trajectory that advances by the same step, again and again: poses first ... last.
struct ConstantMotionRun {
  std::size_t first = 0, last = 0;
  double step_m = 0.0;    ///< length of the run's first step
  double step_deg = 0.0;  ///< rotation of the run's first step
};
/// Stretches of at least `min_steps` steps in which the position moves by the same vector (world frame, within
/// tol_m) and the orientation turns by the same rotation (body frame, within tol_deg) as in the step before;
/// steps shorter than min_step_m (standing still) never count. That is the signature of a gap filled by
/// interpolating (or extrapolating) the position along a line and the orientation at a constant rate. A
/// measured trajectory (GPS/INS, motion capture) does not repeat its steps to a millimetre for a second or more,
/// so per-step errors inside such a run measure the fill, not the odometry (KITTI 00's poses.txt holds several,
/// frames 0-13 among them). A simulated reference may of course move at a constant velocity.
std::vector<ConstantMotionRun> findConstantMotionRuns(const std::vector<Pose3>& poses, double tol_m = 0.002,
                                                      double tol_deg = 0.005, std::size_t min_steps = 10,
                                                      double min_step_m = 0.05);

/// Translation (m) and rotation (rad) of A^-1 * B.
double translationError(const Pose3& a, const Pose3& b);
double rotationErrorRad(const Pose3& a, const Pose3& b);

}  // namespace cosmo::odometry
