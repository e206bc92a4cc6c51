#pragma once
// Ceres cost functions of the JRL Pose3 factors, with GTSAM's error (jrl.md §5): a between factor measuring m
// between poses T1 and T2 has the error r = Log(m^-1 * T1^-1 * T2), a prior p on T the error r = Log(p^-1 * T),
// both in the tangent order [rx, ry, rz, tx, ty, tz] (rotation first, the order of the stored covariance Σ).
// The residual is the whitened error L^-1 r with Σ = L L^T, so that its squared norm is r^T Σ^-1 r.
// A pose is two parameter blocks: an Eigen quaternion [x, y, z, w] (EigenQuaternionManifold) and a translation.
#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cosmo/common/pose.hpp"

namespace cosmo::backend {

/// Log of the pose (q, t) in GTSAM's order: w = the rotation vector of q, v = V(w)^-1 t with
/// V^-1 = I - W/2 + c W² with c = (1 - (θ/2) cot(θ/2)) / θ² (W = [w]x, θ = |w|); below θ² = 0.01 its series
/// 1/12 + θ²/720 + θ⁴/30240 (the closed form cancels there).
template <typename T>
Eigen::Matrix<T, 6, 1> logPose(const Eigen::Quaternion<T>& q, const Eigen::Matrix<T, 3, 1>& t) {
  const T wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  Eigen::Matrix<T, 3, 1> w;
  ceres::QuaternionToAngleAxis(wxyz, w.data());
  Eigen::Matrix<T, 3, 3> W;
  W << T(0), -w(2), w(1), w(2), T(0), -w(0), -w(1), w(0), T(0);
  const T theta2 = w.squaredNorm();
  T c = T(1.0 / 12.0) + theta2 * (T(1.0 / 720.0) + theta2 * T(1.0 / 30240.0));
  if (theta2 > T(1e-2)) {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T theta = sqrt(theta2);
    c = (T(1) - theta * sin(theta) / (T(2) * (T(1) - cos(theta)))) / theta2;
  }
  Eigen::Matrix<T, 6, 1> out;
  out.template head<3>() = w;
  out.template tail<3>() = t - T(0.5) * (W * t) + c * (W * (W * t));
  return out;
}

/// L^-1 for Σ = L L^T (Σ symmetric positive definite; the caller checks).
inline Matrix6 whitener(const Matrix6& covariance) {
  const Eigen::LLT<Matrix6> llt(covariance);
  return llt.matrixL().solve(Matrix6::Identity());
}

/// Between factor: parameters q1, t1, q2, t2.
class BetweenResidual {
 public:
  BetweenResidual(const Pose3& measured, const Matrix6& covariance)
      : m_inv_q_(Eigen::Quaterniond(measured.linear()).conjugate()),
        m_t_(measured.translation()),
        whitener_(whitener(covariance)) {}

  template <typename T>
  bool operator()(const T* q1p, const T* t1p, const T* q2p, const T* t2p, T* out) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q1(q1p), q2(q2p);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t1(t1p), t2(t2p);
    const Eigen::Quaternion<T> q12 = q1.conjugate() * q2;
    const Eigen::Matrix<T, 3, 1> t12 = q1.conjugate() * (t2 - t1);
    const Eigen::Quaternion<T> m_inv = m_inv_q_.cast<T>();
    const Eigen::Matrix<T, 6, 1> r = logPose<T>(m_inv * q12, m_inv * (t12 - m_t_.cast<T>()));
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residual(out);
    residual = whitener_.cast<T>() * r;
    return true;
  }

  static ceres::CostFunction* create(const Pose3& measured, const Matrix6& covariance) {
    return new ceres::AutoDiffCostFunction<BetweenResidual, 6, 4, 3, 4, 3>(new BetweenResidual(measured, covariance));
  }

 private:
  Eigen::Quaterniond m_inv_q_;
  Eigen::Vector3d m_t_;
  Matrix6 whitener_;
};

/// Prior factor: parameters q, t.
class PriorResidual {
 public:
  PriorResidual(const Pose3& prior, const Matrix6& covariance)
      : p_inv_q_(Eigen::Quaterniond(prior.linear()).conjugate()),
        p_t_(prior.translation()),
        whitener_(whitener(covariance)) {}

  template <typename T>
  bool operator()(const T* qp, const T* tp, T* out) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q(qp);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(tp);
    const Eigen::Quaternion<T> p_inv = p_inv_q_.cast<T>();
    const Eigen::Matrix<T, 6, 1> r = logPose<T>(p_inv * q, p_inv * (t - p_t_.cast<T>()));
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residual(out);
    residual = whitener_.cast<T>() * r;
    return true;
  }

  static ceres::CostFunction* create(const Pose3& prior, const Matrix6& covariance) {
    return new ceres::AutoDiffCostFunction<PriorResidual, 6, 4, 3>(new PriorResidual(prior, covariance));
  }

 private:
  Eigen::Quaterniond p_inv_q_;
  Eigen::Vector3d p_t_;
  Matrix6 whitener_;
};

}  // namespace cosmo::backend
