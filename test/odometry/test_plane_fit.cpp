// Plane fits of LOAM's map neighbours: the flatness test (max_plane_planarity) rejects neighbours that straddle
// two surfaces and keeps flat ones, noisy ones included; off (0) it leaves the fit rules unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cosmo/odometry/feature_correspondences.hpp"

using namespace cosmo;

namespace {
/// Four ground points (z = -1.5) and one on a wall foot 10 cm above the ground: a "plane" tilted by the wall point
/// that still passes the mean-distance rule (0.2 m).
std::vector<Eigen::Vector3d> groundAndWallFoot() {
  return {{10.0, 0.0, -1.5}, {10.1, 0.15, -1.5}, {9.9, 0.3, -1.5}, {10.05, 0.45, -1.5}, {10.3, 0.2, -1.40}};
}

/// Five points of one plane (z = -1.5) spread over 0.4 x 0.45 m, with `noise` (m, uniform) in z.
std::vector<Eigen::Vector3d> flatPatch(double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> n(-noise, noise);
  return {{10.0, 0.0, -1.5 + n(rng)}, {10.2, 0.15, -1.5 + n(rng)}, {9.9, 0.3, -1.5 + n(rng)},
          {10.1, 0.45, -1.5 + n(rng)}, {10.3, 0.2, -1.5 + n(rng)}};
}
}  // namespace

TEST(PlaneFit, TwoSurfacesPassTheDefaultRulesButFailTheFlatnessTest) {
  LoamParams p;  // default: flatness test off
  ASSERT_EQ(p.max_plane_planarity, 0.0);
  const auto tilted = fitPlaneConstraint(groundAndWallFoot(), p);
  ASSERT_TRUE(tilted.has_value());
  // The wall point tilts the fitted normal away from the vertical by a clearly measurable angle.
  EXPECT_GT(std::acos(std::abs(tilted->normal.z())), 0.05);
  p.max_plane_planarity = 0.01;
  EXPECT_FALSE(fitPlaneConstraint(groundAndWallFoot(), p).has_value());
}

TEST(PlaneFit, FlatNeighboursPassTheFlatnessTest) {
  LoamParams p;
  p.max_plane_planarity = 0.01;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto c = fitPlaneConstraint(flatPatch(0.005, seed), p);
    ASSERT_TRUE(c.has_value()) << "seed " << seed;
    EXPECT_GT(std::abs(c->normal.z()), 0.999) << "seed " << seed;
    const Eigen::Vector3d centre(10.1, 0.22, -1.5);  // on the true plane, amid the neighbours
    EXPECT_LT(std::abs(c->normal.dot(centre) - c->offset), 0.01) << "seed " << seed;
  }
}

TEST(PlaneFit, FlatnessTestOffKeepsTheFitsUnchanged) {
  LoamParams off, huge;
  huge.max_plane_planarity = 1e9;  // accepts any neighbour set: same fits as off
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto nb = flatPatch(0.05, seed);
    const auto a = fitPlaneConstraint(nb, off), b = fitPlaneConstraint(nb, huge);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_EQ(a->normal, b->normal);
      EXPECT_EQ(a->offset, b->offset);
    }
  }
}
