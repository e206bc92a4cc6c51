#pragma once
// A pose as one Ceres parameter block of 7 numbers [qx, qy, qz, qw, tx, ty, tz] (an Eigen quaternion's coeffs,
// then the translation) on the manifold SE(3) with GTSAM's right perturbation in the tangent order
// [wx, wy, wz, vx, vy, vz]: x ⊕ δ = (q ⊗ Exp(w), t + R(q) v), to first order T · Exp(δ).
// Its PlusJacobian P = diag(½ Q(q), R(q)) (Q(q) = d(q ⊗ [w, 0])/dw, orthonormal columns for a unit q) has the
// pseudo-inverse P⁺ = diag(2 Q(q)ᵀ, R(q)ᵀ): a cost function that knows its Jacobian J on the tangent space reports
// J P⁺ on the 7 numbers, which is the exact derivative of a residual that normalises q, and Ceres' product
// (J P⁺) P gives back J.
#include <ceres/manifold.h>

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cosmo/common/pose.hpp"

namespace cosmo::backend {

using Matrix67 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;  // Ceres' Jacobian layout
using Matrix66 = Eigen::Matrix<double, 6, 6>;

/// Q(q): the 4x3 derivative of q ⊗ [w, 0] by w, rows in Eigen's coeffs order [x, y, z, w].
inline Eigen::Matrix<double, 4, 3> quaternionRightProduct(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 4, 3> Q;
  Q.topRows<3>() = q.w() * Eigen::Matrix3d::Identity() + skew(q.vec());
  Q.row(3) = -q.vec().transpose();
  return Q;
}

/// The unit quaternion of the rotation vector w.
inline Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  const double s = theta < 1e-6 ? 0.5 - theta * theta / 48.0 : std::sin(0.5 * theta) / theta;
  return {std::cos(0.5 * theta), s * w.x(), s * w.y(), s * w.z()};
}

/// J (on the tangent [w, v]) -> J P⁺ (on [q, t]) at the pose (q, R).
inline Matrix67 toAmbient(const Matrix66& J, const Eigen::Quaterniond& q, const Eigen::Matrix3d& R) {
  Matrix67 out;
  out.leftCols<4>().noalias() = 2.0 * J.leftCols<3>() * quaternionRightProduct(q).transpose();
  out.rightCols<3>().noalias() = J.rightCols<3>() * R.transpose();
  return out;
}

class PoseManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(x);
    const Eigen::Map<const Eigen::Vector3d> t(x + 4), w(delta), v(delta + 3);
    Eigen::Map<Eigen::Quaterniond> q_out(x_plus_delta);
    Eigen::Map<Eigen::Vector3d> t_out(x_plus_delta + 4);
    t_out = t + q * v;
    q_out = (q * quaternionExp(w)).normalized();
    return true;
  }

  bool PlusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(x);
    Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> P(jacobian);
    P.setZero();
    P.topLeftCorner<4, 3>() = 0.5 * quaternionRightProduct(q);
    P.bottomRightCorner<3, 3>() = q.toRotationMatrix();
    return true;
  }

  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    const Eigen::Map<const Eigen::Quaterniond> qx(x), qy(y);
    const Eigen::Map<const Eigen::Vector3d> tx(x + 4), ty(y + 4);
    Eigen::Map<Eigen::Vector3d> w(y_minus_x), v(y_minus_x + 3);
    w = logSO3((qx.conjugate() * qy).toRotationMatrix());
    v = qx.conjugate() * (ty - tx);
    return true;
  }

  bool MinusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(x);
    Eigen::Map<Matrix67> M(jacobian);
    M.setZero();
    M.topLeftCorner<3, 4>() = 2.0 * quaternionRightProduct(q).transpose();
    M.bottomRightCorner<3, 3>() = q.toRotationMatrix().transpose();
    return true;
  }
};

}  // namespace cosmo::backend
