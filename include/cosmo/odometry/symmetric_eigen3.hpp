#pragma once
// Closed-form eigenvalues and eigenvectors of a symmetric 3x3 matrix (a point set's scatter), cheaper than
// Eigen's SelfAdjointEigenSolver::computeDirect for the line / plane fits of the LOAM correspondences: the
// eigenvalues by the trigonometric solution of the characteristic cubic (one acos, two cos), an eigenvector as
// the largest cross product of two rows of (A - lambda I), only for the eigenvalue that is needed.
#include <Eigen/Core>

namespace cosmo::odometry {

/// Eigenvalues of the symmetric `a` (only its upper triangle is read), ascending.
Eigen::Vector3d symmetricEigenvalues3(const Eigen::Matrix3d& a);

/// Unit eigenvector of the symmetric `a` for its eigenvalue `lambda` (accurate when lambda is separated from
/// the other two eigenvalues; some unit vector of the eigenspace otherwise; +x for a multiple of I).
Eigen::Vector3d symmetricEigenvector3(const Eigen::Matrix3d& a, double lambda);

/// Some unit vector perpendicular to the unit vector `u`.
Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& u);

}  // namespace cosmo::odometry
