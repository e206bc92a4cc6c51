#include "cosmo/odometry/symmetric_eigen3.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>  // cross()

namespace cosmo::odometry {

Eigen::Vector3d symmetricEigenvalues3(const Eigen::Matrix3d& a) {
  const double a00 = a(0, 0), a11 = a(1, 1), a22 = a(2, 2), a01 = a(0, 1), a02 = a(0, 2), a12 = a(1, 2);
  const double q = (a00 + a11 + a22) / 3.0;
  const double p1 = a01 * a01 + a02 * a02 + a12 * a12;
  const double b00 = a00 - q, b11 = a11 - q, b22 = a22 - q;
  const double p2 = b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * p1;
  if (!(p2 > 0.0)) return Eigen::Vector3d::Constant(q);  // a multiple of I (or NaN: propagated through q)
  const double p = std::sqrt(p2 / 6.0);
  // det((A - qI) / p) / 2, in [-1, 1] up to rounding.
  const double det = b00 * (b11 * b22 - a12 * a12) - a01 * (a01 * b22 - a12 * a02) + a02 * (a01 * a12 - b11 * a02);
  const double r = std::clamp(det / (2.0 * p * p * p), -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;  // in [0, pi / 3]
  const double c = std::cos(phi), s = std::sqrt(std::max(0.0, 1.0 - c * c));
  constexpr double kHalfSqrt3 = 0.86602540378443864676;
  const double largest = q + 2.0 * p * c;
  const double smallest = q + 2.0 * p * (-0.5 * c - kHalfSqrt3 * s);  // cos(phi + 2 pi / 3)
  const double middle = 3.0 * q - largest - smallest;
  return {smallest, std::clamp(middle, smallest, largest), largest};
}

Eigen::Vector3d symmetricEigenvector3(const Eigen::Matrix3d& a, double lambda) {
  const Eigen::Vector3d r0(a(0, 0) - lambda, a(0, 1), a(0, 2));
  const Eigen::Vector3d r1(a(0, 1), a(1, 1) - lambda, a(1, 2));
  const Eigen::Vector3d r2(a(0, 2), a(1, 2), a(2, 2) - lambda);
  const Eigen::Vector3d c01 = r0.cross(r1), c02 = r0.cross(r2), c12 = r1.cross(r2);
  const double n01 = c01.squaredNorm(), n02 = c02.squaredNorm(), n12 = c12.squaredNorm();
  if (n01 >= n02 && n01 >= n12 && n01 > 0.0) return c01 / std::sqrt(n01);
  if (n02 >= n12 && n02 > 0.0) return c02 / std::sqrt(n02);
  if (n12 > 0.0) return c12 / std::sqrt(n12);
  // Rank <= 1 for (A - lambda I): a double eigenvalue; any vector perpendicular to the remaining row.
  const Eigen::Vector3d* rows[3] = {&r0, &r1, &r2};
  const Eigen::Vector3d* best = rows[0];
  for (const Eigen::Vector3d* row : rows)
    if (row->squaredNorm() > best->squaredNorm()) best = row;
  if (best->squaredNorm() > 0.0) return anyPerpendicular(best->normalized());
  return Eigen::Vector3d::UnitX();
}

Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& u) {
  // Cross with the axis least aligned with u.
  const Eigen::Vector3d au = u.cwiseAbs();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  if (au.y() <= au.x() && au.y() <= au.z())
    axis = Eigen::Vector3d::UnitY();
  else if (au.z() <= au.x() && au.z() <= au.y())
    axis = Eigen::Vector3d::UnitZ();
  return u.cross(axis).normalized();
}

}  // namespace cosmo::odometry
