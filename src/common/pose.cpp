#include "cosmo/common/pose.hpp"

#include <cmath>

namespace cosmo {

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return S;
}

Eigen::Matrix3d expSO3(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  if (theta < 1e-12) return Eigen::Matrix3d::Identity() + skew(w);
  return Eigen::AngleAxisd(theta, w / theta).toRotationMatrix();
}

Eigen::Vector3d logSO3(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(Eigen::Quaterniond(R).normalized());
  double angle = aa.angle();
  Eigen::Vector3d axis = aa.axis();
  if (angle > M_PI) {  // Eigen may return angles in (pi, 2pi)
    angle = 2.0 * M_PI - angle;
    axis = -axis;
  }
  return axis * angle;
}

namespace {
// Left Jacobian of SO(3), V in T = [R, V v].
Eigen::Matrix3d leftJacobianSO3(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  const Eigen::Matrix3d W = skew(w);
  if (theta < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 6.0;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * W +
         (theta - std::sin(theta)) / (t2 * theta) * W * W;
}
}  // namespace

Pose3 expSE3(const Vector6& xi) {
  const Eigen::Vector3d w = xi.head<3>();
  Pose3 T = Pose3::Identity();
  T.linear() = expSO3(w);
  T.translation() = leftJacobianSO3(w) * xi.tail<3>();
  return T;
}

Vector6 logSE3(const Pose3& T) {
  Vector6 xi;
  const Eigen::Vector3d w = logSO3(T.linear());
  xi.head<3>() = w;
  xi.tail<3>() = leftJacobianSO3(w).inverse() * T.translation();
  return xi;
}

Pose3 makePose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Pose3 T = Pose3::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

Pose3 makePose(double x, double y, double z, double roll, double pitch, double yaw) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return makePose(Eigen::Vector3d(x, y, z), q);
}

double rotationAngle(const Pose3& T) { return logSO3(T.linear()).norm(); }

double yawOf(const Pose3& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

Pose3 interpolate(const Pose3& a, const Pose3& b, double s) {
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  return makePose((1.0 - s) * a.translation() + s * b.translation(), qa.slerp(s, qb));
}

Pose3 orthonormalized(const Pose3& T) { return makePose(T.translation(), Eigen::Quaterniond(T.linear()).normalized()); }

}  // namespace cosmo
