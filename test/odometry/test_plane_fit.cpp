// Plane fits of LOAM's map neighbours: the flatness test (max_plane_planarity) rejects neighbours that straddle
// two surfaces and keeps flat ones, noisy ones included; off (0) it leaves the fit rules unchanged. The
// off-surface test (plane_off_surface_min_dist, on by default) rejects a set made uneven by one neighbour and keeps
// more of the sets uneven as a whole.
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
  return {{10.0, 0.0, -1.5 + n(rng)},
          {10.2, 0.15, -1.5 + n(rng)},
          {9.9, 0.3, -1.5 + n(rng)},
          {10.1, 0.45, -1.5 + n(rng)},
          {10.3, 0.2, -1.5 + n(rng)}};
}

/// The paper's fit rules only: both of our neighbour tests off.
odometry::LoamParams paperRules() {
  odometry::LoamParams p;
  p.max_plane_planarity = 0.0;
  p.plane_off_surface_min_dist = 0.0;
  return p;
}
}  // namespace

TEST(PlaneFit, TwoSurfacesPassThePaperRulesButFailTheFlatnessTest) {
  ASSERT_EQ(odometry::LoamParams{}.max_plane_planarity, 0.0);  // off by default
  odometry::LoamParams p = paperRules();
  const auto tilted = fitPlaneConstraint(groundAndWallFoot(), p);
  ASSERT_TRUE(tilted.has_value());
  // The wall point tilts the fitted normal away from the vertical by a clearly measurable angle.
  EXPECT_GT(std::acos(std::abs(tilted->normal.z())), 0.05);
  p.max_plane_planarity = 0.01;
  EXPECT_FALSE(fitPlaneConstraint(groundAndWallFoot(), p).has_value());
}

TEST(PlaneFit, FlatNeighboursPassTheFlatnessTest) {
  odometry::LoamParams p = paperRules();
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
  odometry::LoamParams off = paperRules(), huge = paperRules();
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

TEST(PlaneFit, OffSurfaceTestRejectsOneWallPointAmongGroundPoints) {
  ASSERT_EQ(odometry::LoamParams{}.plane_off_surface_min_dist, 0.02);  // on by default
  odometry::LoamParams p = paperRules();
  ASSERT_TRUE(fitPlaneConstraint(groundAndWallFoot(), p).has_value());
  p.plane_off_surface_min_dist = 0.01;  // the set spreads 1.9 cm along its fitted normal
  EXPECT_FALSE(fitPlaneConstraint(groundAndWallFoot(), p).has_value());
  p.plane_off_surface_min_dist = 0.05;  // more than it spreads: kept
  EXPECT_TRUE(fitPlaneConstraint(groundAndWallFoot(), p).has_value());
}

TEST(PlaneFit, OffSurfaceTestKeepsSetsUnevenAsAWhole) {
  // Patches uneven by +-4 cm everywhere (no single neighbour to blame): the flatness test rejects half of them
  // (25 of 50), the off-surface test a third (16: with five random points, one is sometimes the odd one out).
  odometry::LoamParams flatness = paperRules(), off_surface = paperRules();
  flatness.max_plane_planarity = 0.01;
  off_surface.plane_off_surface_min_dist = 0.01;
  int kept_flatness = 0, kept_off_surface = 0;
  constexpr int kPatches = 50;
  for (std::uint64_t seed = 1; seed <= kPatches; ++seed) {
    const auto nb = flatPatch(0.04, seed);
    kept_flatness += fitPlaneConstraint(nb, flatness).has_value() ? 1 : 0;
    kept_off_surface += fitPlaneConstraint(nb, off_surface).has_value() ? 1 : 0;
  }
  EXPECT_GT(kept_off_surface, kPatches / 2 + kPatches / 10);
  EXPECT_GT(kept_off_surface, kept_flatness + kPatches / 10);
}

TEST(PlaneFit, OffSurfaceTestKeepsFlatNeighboursUnchanged) {
  odometry::LoamParams off = paperRules(), on = paperRules();
  on.plane_off_surface_min_dist = 0.02;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto nb = flatPatch(0.005, seed);
    const auto a = fitPlaneConstraint(nb, off), b = fitPlaneConstraint(nb, on);
    ASSERT_TRUE(a.has_value() && b.has_value()) << "seed " << seed;
    EXPECT_EQ(a->normal, b->normal);
    EXPECT_EQ(a->offset, b->offset);
  }
}
