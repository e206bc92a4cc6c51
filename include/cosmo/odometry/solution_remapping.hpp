#pragma once
// Gauss-Newton solve with solution remapping (Zhang, Kaess & Singh 2016, "On degeneracy of optimization-based
// state estimation problems"): directions the constraints do not determine keep their current value.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace cosmo::odometry {

/// The step dx solving H dx = -g in H's eigenbasis, with the components along eigenvectors whose eigenvalue is
/// below `min_eigenvalue` set to 0; `degenerate`: how many were.
template <int N>
Eigen::Matrix<double, N, 1> remappedGaussNewtonStep(const Eigen::Matrix<double, N, N>& H,
                                                    const Eigen::Matrix<double, N, 1>& g, double min_eigenvalue,
                                                    int& degenerate) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> es(H);
  Eigen::Matrix<double, N, 1> coeff = es.eigenvectors().transpose() * g;
  degenerate = 0;
  for (int i = 0; i < N; ++i) {
    if (es.eigenvalues()[i] < min_eigenvalue) {
      coeff[i] = 0.0;
      ++degenerate;
    } else {
      coeff[i] /= es.eigenvalues()[i];
    }
  }
  return -(es.eigenvectors() * coeff);
}

}  // namespace cosmo::odometry
