#include "cosmo/odometry/trajectory_metrics.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cosmo::odometry {

Pose3 umeyamaAlignment(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target) {
  if (source.size() != target.size()) throw std::invalid_argument("umeyamaAlignment: size mismatch");
  Pose3 A = Pose3::Identity();
  if (source.empty()) return A;
  const double n = static_cast<double>(source.size());
  Eigen::Vector3d ms = Eigen::Vector3d::Zero(), mt = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) {
    ms += source[i];
    mt += target[i];
  }
  ms /= n;
  mt /= n;
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) C += (target[i] - mt) * (source[i] - ms).transpose();
  C /= n;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
  const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();
  A.linear() = R;
  A.translation() = mt - R * ms;
  return A;
}

AteResult absoluteTrajectoryError(const std::vector<Pose3>& estimate, const std::vector<Pose3>& reference) {
  if (estimate.size() != reference.size()) throw std::invalid_argument("absoluteTrajectoryError: size mismatch");
  AteResult r;
  if (estimate.empty()) return r;
  std::vector<Eigen::Vector3d> s, t;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    s.push_back(estimate[i].translation());
    t.push_back(reference[i].translation());
  }
  r.alignment = umeyamaAlignment(s, t);
  double sum2 = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double e = (r.alignment * s[i] - t[i]).norm();
    sum2 += e * e;
    sum += e;
    r.max = std::max(r.max, e);
  }
  r.rmse = std::sqrt(sum2 / static_cast<double>(s.size()));
  r.mean = sum / static_cast<double>(s.size());
  return r;
}

double translationError(const Pose3& a, const Pose3& b) { return (a.inverse() * b).translation().norm(); }
double rotationErrorRad(const Pose3& a, const Pose3& b) { return rotationAngle(a.inverse() * b); }

std::vector<SegmentError> segmentErrors(const std::vector<Pose3>& estimate, const std::vector<Pose3>& reference,
                                        const std::vector<double>& lengths, std::size_t step) {
  if (estimate.size() != reference.size()) throw std::invalid_argument("segmentErrors: size mismatch");
  step = std::max<std::size_t>(1, step);
  std::vector<double> dist(reference.size(), 0.0);
  for (std::size_t i = 1; i < reference.size(); ++i)
    dist[i] = dist[i - 1] + (reference[i].translation() - reference[i - 1].translation()).norm();
  std::vector<SegmentError> out;
  for (double L : lengths) {
    SegmentError e;
    e.length = L;
    double tsum = 0.0, rsum = 0.0;
    std::size_t j = 0;
    for (std::size_t i = 0; i < reference.size(); i += step) {
      j = std::max(j, i);
      while (j < reference.size() && dist[j] - dist[i] < L) ++j;
      if (j >= reference.size()) break;
      const Pose3 dg = reference[i].inverse() * reference[j];
      const Pose3 de = estimate[i].inverse() * estimate[j];
      const Pose3 err = de.inverse() * dg;
      tsum += err.translation().norm() / L;
      rsum += rotationAngle(err) / L;
      ++e.count;
    }
    if (e.count > 0) {
      e.translation_percent = 100.0 * tsum / static_cast<double>(e.count);
      e.rotation_deg_per_m = rsum / static_cast<double>(e.count) * 180.0 / M_PI;
    }
    out.push_back(e);
  }
  return out;
}

std::vector<ConstantMotionRun> findConstantMotionRuns(const std::vector<Pose3>& poses, double tol_m, double tol_deg,
                                                      std::size_t min_steps, double min_step_m) {
  std::vector<ConstantMotionRun> runs;
  const double tol_rad = tol_deg * M_PI / 180.0;
  std::size_t start = 0;               // first pose of the current run of equal steps
  auto close = [&](std::size_t end) {  // the run's last pose
    if (end > start && end - start >= min_steps) {
      const Pose3 d = poses[start].inverse() * poses[start + 1];
      runs.push_back({start, end, d.translation().norm(), rotationAngle(d) * 180.0 / M_PI});
    }
  };
  for (std::size_t i = 1; i + 1 < poses.size(); ++i) {
    // A fill interpolates the position along a straight line and the orientation at a constant rate, each on
    // its own: the position steps are equal in the world frame, the rotation steps in the body frame.
    const Eigen::Vector3d move_before = poses[i].translation() - poses[i - 1].translation();
    const Eigen::Vector3d move_after = poses[i + 1].translation() - poses[i].translation();
    const Eigen::Matrix3d turn_before = poses[i - 1].linear().transpose() * poses[i].linear();
    const Eigen::Matrix3d turn_after = poses[i].linear().transpose() * poses[i + 1].linear();
    const bool moving = move_before.norm() >= min_step_m && move_after.norm() >= min_step_m;
    if (moving && (move_after - move_before).norm() <= tol_m &&
        Eigen::AngleAxisd(turn_before.transpose() * turn_after).angle() <= tol_rad)
      continue;
    close(i);
    start = i;
  }
  if (poses.size() >= 2) close(poses.size() - 1);
  return runs;
}

}  // namespace cosmo::odometry
