#include "cosmo/odometry/continuous_rotation_refine.hpp"

#include <algorithm>
#include <cmath>

#include "cosmo/odometry/solution_remapping.hpp"

namespace cosmo::odometry {

FeatureRegistrationResult refineContinuousRotation(const LoamFeatures& features, FeatureRegistrationResult previous,
                                                   const LoamParams& params, const Pose3& previous_pose,
                                                   const Pose3& predicted_delta, double period, double tie,
                                                   int max_steps) {
  FeatureRegistrationResult res = std::move(previous);
  if (res.constraints.empty() || !(period > 0.0)) return res;
  using Matrix9 = Eigen::Matrix<double, 9, 9>;
  using Vector9 = Eigen::Matrix<double, 9, 1>;
  // Unknowns: [stamp rotation, stamp translation] (centred update) and the start rotation (world frame).
  Eigen::Matrix3d start = res.pose.linear() * predicted_delta.linear().transpose();
  const Eigen::Matrix3d tied_to = previous_pose.linear();
  const double min_ev = params.min_eigenvalue_per_constraint * static_cast<double>(res.constraints.size());
  std::vector<Eigen::Vector3d> edges, planes;
  for (int step = 0; step < max_steps; ++step) {
    Pose3 sweep = predicted_delta;
    sweep.linear() = start.transpose() * res.pose.linear();
    deskewFeatures(features, sweep, period, edges, planes);
    Matrix9 H = Matrix9::Zero();
    Vector9 g = Vector9::Zero();
    Eigen::Matrix3d rigid_rotation_info = Eigen::Matrix3d::Zero();
    const Eigen::Vector3d centre = res.pose.translation();
    for (auto& c : res.constraints) {
      c.point = c.edge ? edges[c.feature] : planes[c.feature];
      const auto& times = c.edge ? features.edge_time : features.planar_time;
      const double t = c.feature < times.size() ? static_cast<double>(times[c.feature]) : 0.0;
      const double s = std::clamp(1.0 + t / period, 0.0, 1.0);
      const Eigen::Vector3d q = res.pose * c.point;
      const double r = c.normal.dot(q) - c.offset;
      const Eigen::Vector3d turn = (q - centre).cross(c.normal);  // d r / d rotation, rigid
      Vector9 J;
      J << s * turn, c.normal, (1.0 - s) * turn;
      const double a = std::abs(r);
      const double w = a <= params.huber_delta ? 1.0 : params.huber_delta / a;
      H.noalias() += w * J * J.transpose();
      g.noalias() += w * r * J;
      rigid_rotation_info.noalias() += w * turn * turn.transpose();
    }
    const double weight = tie * rigid_rotation_info.trace() / 3.0;
    H.block<3, 3>(6, 6) += weight * Eigen::Matrix3d::Identity();
    g.tail<3>() += weight * logSO3(start * tied_to.transpose());
    int degenerate = 0;
    const Vector9 dx = remappedGaussNewtonStep<9>(H, g, min_ev, degenerate);
    res.degenerate_directions = std::min(degenerate, 6);
    res.pose = applyCentredUpdate(dx.head<6>(), res.pose);
    start = expSO3(dx.tail<3>()) * start;
    if (dx.head<3>().norm() < params.rotation_convergence_thresh &&
        dx.tail<3>().norm() < params.rotation_convergence_thresh &&
        dx.segment<3>(3).norm() < params.position_convergence_thresh)
      break;
  }
  res.sweep_rotation = start.transpose() * res.pose.linear();
  res.iterations += 1;
  res.inlier_fraction = inlierFraction(res.constraints, res.pose, params.inlier_dist, features.size());
  return res;
}

}  // namespace cosmo::odometry
