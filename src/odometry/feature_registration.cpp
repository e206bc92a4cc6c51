#include "cosmo/odometry/feature_registration.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "cosmo/odometry/dewarp.hpp"
#include "cosmo/odometry/solution_remapping.hpp"

namespace cosmo::odometry {

Pose3 applyCentredUpdate(const Vector6& dx, const Pose3& T) {
  Pose3 to_centre = Pose3::Identity();
  to_centre.translation() = T.translation();
  return orthonormalized(to_centre * expSE3(dx) * to_centre.inverse() * T);
}

Vector6 robustGaussNewtonStep(const std::vector<FeatureConstraint>& constraints, const Pose3& T, double huber_delta,
                              double min_eigenvalue_per_constraint, int& degenerate) {
  Matrix6 H = Matrix6::Zero();
  Vector6 g = Vector6::Zero();
  // Perturbation about the sensor position (see applyCentredUpdate): lever arms are the features' ranges, not
  // their distances from the odometry origin, so the eigenvalues (degeneracy test) do not depend on how far
  // the robot has travelled.
  const Eigen::Vector3d centre = T.translation();
  for (const auto& c : constraints) {
    const Eigen::Vector3d q = T * c.point;
    const double r = c.normal.dot(q) - c.offset;
    Vector6 J;
    J.head<3>() = (q - centre).cross(c.normal);  // d r / d omega for a rotation about the sensor position
    J.tail<3>() = c.normal;
    const double a = std::abs(r);
    const double w = a <= huber_delta ? 1.0 : huber_delta / a;
    H.noalias() += w * J * J.transpose();
    g.noalias() += w * r * J;
  }
  degenerate = 0;
  if (constraints.empty()) {
    degenerate = 6;
    return Vector6::Zero();
  }
  return remappedGaussNewtonStep<6>(H, g, min_eigenvalue_per_constraint * static_cast<double>(constraints.size()),
                                    degenerate);
}

double scorePose(const LoamFeatures& features, const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                 std::size_t stride) {
  std::vector<FeatureConstraint> cs;
  associateFeatures(features.edge_points, features.planar_points, map, T, params, cs, stride);
  const std::size_t n =
      (features.edge_points.size() + stride - 1) / stride + (features.planar_points.size() + stride - 1) / stride;
  if (n == 0) return 0.0;
  std::size_t good = 0;
  for (const auto& c : cs)
    if (std::abs(c.normal.dot(T * c.point) - c.offset) < params.inlier_dist) ++good;
  return static_cast<double>(good) / static_cast<double>(n);
}

namespace {
/// Every `stride`-th element (all when stride == 1).
template <typename T>
std::vector<T> subsample(const std::vector<T>& v, std::size_t stride) {
  if (stride <= 1) return v;
  std::vector<T> out;
  out.reserve(v.size() / stride + 1);
  for (std::size_t i = 0; i < v.size(); i += stride) out.push_back(v[i]);
  return out;
}
}  // namespace

FeatureRegistrationResult registerFeatures(const LoamFeatures& features, const LocalFeatureMap& map, const Pose3& guess,
                                           const LoamParams& params, const std::optional<DeskewReference>& deskew) {
  FeatureRegistrationResult res;
  res.pose = guess;
  const bool do_deskew =
      deskew && params.deskew && deskew->period > 0.0 && (!features.edge_time.empty() || !features.planar_time.empty());
  std::vector<FeatureConstraint> cs;
  std::vector<Eigen::Vector3d> edges, planes;

  // Coarse-to-fine: a subsample of the features (about params.coarse_features), then all features. Each stage:
  // associate, then a few Gauss-Newton steps with the association fixed; repeat until an association round moves
  // the pose less than the thresholds.
  const std::size_t n_all = features.size();
  const std::size_t coarse_stride = std::max<std::size_t>(1, n_all / static_cast<std::size_t>(params.coarse_features));
  struct Stage {
    std::size_t stride;
    double pos_thresh, rot_thresh;
  };
  std::vector<Stage> stages;
  // The subsample converges to the thresholds (cheap), then all features polish it: usually one association
  // round, repeated only while a round moves the pose by more than fine_convergence_factor times the thresholds.
  if (coarse_stride > 1) {
    const double fine = params.fine_convergence_factor;
    stages.push_back({coarse_stride, params.position_convergence_thresh, params.rotation_convergence_thresh});
    stages.push_back({1, fine * params.position_convergence_thresh, fine * params.rotation_convergence_thresh});
  } else {
    stages.push_back({1, params.position_convergence_thresh, params.rotation_convergence_thresh});
  }

  // Association memory over all rounds: a feature whose query point moved less than its reuse radius keeps its
  // neighbours and fit without a new k-NN search (the same constraint as a new search would give).
  AssociationMemory memory;
  memory.reset(features.edge_points.size(), features.planar_points.size());
  int rounds = 0;
  for (std::size_t si = 0; si < stages.size(); ++si) {
    const Stage& st = stages[si];
    const bool last_stage = (si + 1 == stages.size());
    LoamFeatures f;
    f.edge_points = subsample(features.edge_points, st.stride);
    f.planar_points = subsample(features.planar_points, st.stride);
    f.edge_time = subsample(features.edge_time, st.stride);
    f.planar_time = subsample(features.planar_time, st.stride);
    if (do_deskew) {
      deskewFeatures(f, deskew->delta, deskew->period, edges, planes);
    } else {
      edges = f.edge_points;
      planes = f.planar_points;
    }
    // The pose two association rounds ago: a subsample whose association flips one feature in and out
    // alternates between two poses for good. The stage stops once two rounds in a row return to within the
    // thresholds of the pose two rounds back (one return alone also happens while a large motion converges).
    Pose3 two_back = res.pose;
    bool returned = false;  // the previous round came back to the pose two rounds before it
    for (int it = 0; it < params.max_icf_iterations; ++it) {
      // The last stage of two (all features) only reads the memory: its features mostly associate once, and
      // the (k+1)-th neighbour that remembering needs costs more than the reuse saves.
      associateFeaturesRemembering(edges, planes, map, res.pose, params, cs, memory, st.stride,
                                   !last_stage || stages.size() == 1);
      ++rounds;
      const Pose3 before = res.pose;
      for (int k = 0; k < params.icf_inner_steps; ++k) {
        int degenerate = 0;
        const Vector6 dx =
            robustGaussNewtonStep(cs, res.pose, params.huber_delta, params.min_eigenvalue_per_constraint, degenerate);
        res.degenerate_directions = degenerate;
        res.pose = applyCentredUpdate(dx, res.pose);
        if (dx.head<3>().norm() < params.rotation_convergence_thresh &&
            dx.tail<3>().norm() < params.position_convergence_thresh)
          break;
      }
      auto within = [&](const Pose3& from) {  // res.pose is within the stage's thresholds of `from`
        const Vector6 moved = logSE3(from.inverse() * res.pose);
        return moved.head<3>().norm() < st.rot_thresh && moved.tail<3>().norm() < st.pos_thresh;
      };
      if (within(before)) {
        if (last_stage) res.converged = true;
        break;
      }
      const bool returns = it >= 1 && within(two_back);
      if (returns && returned) break;  // two returns in a row: a settled two-pose cycle
      returned = returns;
      two_back = before;  // the next round's pose two rounds back
    }
  }
  res.iterations = rounds;
  // Statistics from the last association (the pose has moved by less than the last, small, update since).
  std::size_t good = 0;
  for (const auto& c : cs) {
    (c.edge ? res.num_edge_constraints : res.num_plane_constraints)++;
    if (std::abs(c.normal.dot(res.pose * c.point) - c.offset) < params.inlier_dist) ++good;
  }
  const std::size_t n = features.size();
  res.inlier_fraction = n ? static_cast<double>(good) / static_cast<double>(n) : 0.0;
  res.constraints = std::move(cs);
  return res;
}

void deskewFeatures(const LoamFeatures& features, const Pose3& delta, double period,
                    std::vector<Eigen::Vector3d>& edges, std::vector<Eigen::Vector3d>& planes) {
  deskewConstantVelocity(features.edge_points, features.edge_time, delta, period, edges);
  deskewConstantVelocity(features.planar_points, features.planar_time, delta, period, planes);
}

FeatureRegistrationResult refineRedeskewed(const LoamFeatures& features, FeatureRegistrationResult previous,
                                           const LoamParams& params, const DeskewReference& deskew, int max_steps) {
  FeatureRegistrationResult res = std::move(previous);
  std::vector<Eigen::Vector3d> edges, planes;
  deskewFeatures(features, deskew.delta, deskew.period, edges, planes);
  for (auto& c : res.constraints) c.point = c.edge ? edges[c.feature] : planes[c.feature];
  int steps = 0;
  for (; steps < max_steps; ++steps) {
    int degenerate = 0;
    const Vector6 dx = robustGaussNewtonStep(res.constraints, res.pose, params.huber_delta,
                                             params.min_eigenvalue_per_constraint, degenerate);
    res.degenerate_directions = degenerate;
    res.pose = applyCentredUpdate(dx, res.pose);
    if (dx.head<3>().norm() < params.rotation_convergence_thresh &&
        dx.tail<3>().norm() < params.position_convergence_thresh)
      break;
  }
  res.iterations += 1;
  res.inlier_fraction = inlierFraction(res.constraints, res.pose, params.inlier_dist, features.size());
  return res;
}

double inlierFraction(const std::vector<FeatureConstraint>& constraints, const Pose3& T, double inlier_dist,
                      std::size_t num_features) {
  std::size_t good = 0;
  for (const auto& c : constraints)
    if (std::abs(c.normal.dot(T * c.point) - c.offset) < inlier_dist) ++good;
  return num_features ? static_cast<double>(good) / static_cast<double>(num_features) : 0.0;
}

}  // namespace cosmo::odometry
