// symmetricEigenvalues3 / symmetricEigenvector3 against Eigen's iterative solver on point-set scatters:
// blobs, planes (small smallest eigenvalue), lines (one dominant), far from the origin, and degenerate ones.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "cosmo/odometry/symmetric_eigen3.hpp"

using namespace cosmo;

namespace {
Eigen::Matrix3d scatterOf(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) s += (p - mean) * (p - mean).transpose();
  return s / static_cast<double>(pts.size());
}
}  // namespace

TEST(SymmetricEigen3, MatchesEigenOnPointScatters) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(-500.0, 500.0);
  for (int trial = 0; trial < 3000; ++trial) {
    // Axis scales: blob, plane (thin along one axis), line (long along one axis).
    const int kind = trial % 3;
    const Eigen::Vector3d scale = kind == 0   ? Eigen::Vector3d(1.0, 0.7, 0.4)
                                  : kind == 1 ? Eigen::Vector3d(1.0, 0.5, 0.003)
                                              : Eigen::Vector3d(1.0, 0.02, 0.01);
    const Eigen::Matrix3d R = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    const Eigen::Vector3d centre(u(rng), u(rng), 0.1 * u(rng));
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < 5; ++i) pts.push_back(centre + R * scale.cwiseProduct(Eigen::Vector3d(g(rng), g(rng), g(rng))));
    const Eigen::Matrix3d s = scatterOf(pts);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(s);
    const Eigen::Vector3d ev = odometry::symmetricEigenvalues3(s);
    const double norm = es.eigenvalues().cwiseAbs().maxCoeff();
    // The acos solution is ill-conditioned for two nearly equal eigenvalues (a line's two small ones): their
    // absolute error reaches ~1e-11 of the largest, far below what the fit tests (ratios >= 0.05) resolve.
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(ev[i], es.eigenvalues()[i], 1e-10 * norm + 1e-15) << trial;
    // The eigenvector a fit uses: smallest for planes, largest for lines (well separated there).
    const int which = kind == 1 ? 0 : 2;
    if (kind != 0) {
      const Eigen::Vector3d v = odometry::symmetricEigenvector3(s, ev[which]);
      EXPECT_NEAR(v.norm(), 1.0, 1e-12);
      EXPECT_NEAR(std::abs(v.dot(es.eigenvectors().col(which))), 1.0, 1e-9) << trial;
    }
  }
}

TEST(SymmetricEigen3, DegenerateMatrices) {
  const Eigen::Vector3d same = odometry::symmetricEigenvalues3(2.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(same, Eigen::Vector3d::Constant(2.0));
  EXPECT_NEAR(odometry::symmetricEigenvector3(2.0 * Eigen::Matrix3d::Identity(), 2.0).norm(), 1.0, 1e-12);
  const Eigen::Vector3d zero = odometry::symmetricEigenvalues3(Eigen::Matrix3d::Zero());
  EXPECT_EQ(zero, Eigen::Vector3d::Zero());
  // Rank 1 (collinear points along d): eigenvalues 0, 0, |d|^2; the eigenvector of |d|^2 is d.
  const Eigen::Vector3d d = Eigen::Vector3d(1.0, 2.0, -0.5).normalized() * 3.0;
  const Eigen::Matrix3d rank1 = d * d.transpose();
  const Eigen::Vector3d ev = odometry::symmetricEigenvalues3(rank1);
  EXPECT_NEAR(ev[0], 0.0, 1e-12);
  EXPECT_NEAR(ev[1], 0.0, 1e-12);
  EXPECT_NEAR(ev[2], 9.0, 1e-12);
  EXPECT_NEAR(std::abs(odometry::symmetricEigenvector3(rank1, ev[2]).dot(d.normalized())), 1.0, 1e-12);
  // A perpendicular of the double eigenvalue 0 is perpendicular to d.
  EXPECT_NEAR(odometry::symmetricEigenvector3(rank1, ev[0]).dot(d), 0.0, 1e-9);
  const Eigen::Vector3d p = odometry::anyPerpendicular(Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(p.norm(), 1.0, 1e-12);
  EXPECT_NEAR(p.z(), 0.0, 1e-12);
}
