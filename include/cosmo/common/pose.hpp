#pragma once
// Rigid-body poses and the SE(3) exponential / logarithm in GTSAM's tangent order [rx, ry, rz, tx, ty, tz]
// (rotation first, radians then metres), which is the order JRL covariances use.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cosmo {

using Pose3 = Eigen::Isometry3d;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// so(3) hat operator.
Eigen::Matrix3d skew(const Eigen::Vector3d& w);
/// SO(3) exponential (Rodrigues), exact near zero.
Eigen::Matrix3d expSO3(const Eigen::Vector3d& w);
/// SO(3) logarithm, the rotation vector (angle in [0, pi]).
Eigen::Vector3d logSO3(const Eigen::Matrix3d& R);
/// SE(3) exponential of xi = [w, v] (GTSAM Pose3::Expmap).
Pose3 expSE3(const Vector6& xi);
/// SE(3) logarithm [w, v] (GTSAM Pose3::Logmap), so that expSE3(logSE3(T)) == T.
Vector6 logSE3(const Pose3& T);
/// Pose from translation and quaternion (normalised).
Pose3 makePose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q);
/// Pose from translation and roll/pitch/yaw (ZYX), radians.
Pose3 makePose(double x, double y, double z, double roll, double pitch, double yaw);
/// Rotation angle of a pose's rotation part, radians in [0, pi].
double rotationAngle(const Pose3& T);
/// Yaw (heading about +z) of a pose, radians.
double yawOf(const Pose3& T);
/// Interpolate between two poses: slerp on rotation, linear on translation, s in [0, 1].
Pose3 interpolate(const Pose3& a, const Pose3& b, double s);
/// Re-orthonormalise the rotation part (after long chains of products).
Pose3 orthonormalized(const Pose3& T);

}  // namespace cosmo
