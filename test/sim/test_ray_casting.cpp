// Rays against known primitives and terrain give the known ranges; the BVH agrees with brute force.
#include <gtest/gtest.h>

#include <random>

#include "cosmo/sim/bvh.hpp"
#include "cosmo/sim/material.hpp"
#include "cosmo/sim/terrain.hpp"
#include "cosmo/sim/world.hpp"
#include "cosmo/sim/world_generator.hpp"

using namespace cosmo::sim;
using Eigen::Vector3d;

TEST(RayCasting, BoxGivesKnownRangeAndNormal) {
  const auto box = Primitive::box({10, 0, 1}, {1, 2, 1}, 0.0, kConcrete);
  Hit hit;
  hit.t = 100;
  ASSERT_TRUE(box.intersect(Ray({0, 0, 1}, {1, 0, 0}), 0.0, hit));
  EXPECT_NEAR(hit.t, 9.0, 1e-12);
  EXPECT_NEAR(hit.normal.x(), -1.0, 1e-12);
  // Rotated by 45 deg: the corner points at the ray, at 10 - sqrt(2).
  const auto turned = Primitive::box({10, 0, 1}, {1, 1, 1}, M_PI / 4, kConcrete);
  hit.t = 100;
  ASSERT_TRUE(turned.intersect(Ray({0, 0.3, 1}, {1, 0, 0}), 0.0, hit));
  EXPECT_NEAR(hit.t, 10.0 - std::sqrt(2.0) + 0.3, 1e-9);
  // Miss above.
  hit.t = 100;
  EXPECT_FALSE(box.intersect(Ray({0, 0, 2.5}, {1, 0, 0}), 0.0, hit));
}

TEST(RayCasting, CylinderAndEllipsoidGiveKnownRanges) {
  const auto pole = Primitive::cylinder(5, 0, 0, 6, 0.5, kMetal);
  Hit hit;
  hit.t = 100;
  ASSERT_TRUE(pole.intersect(Ray({0, 0, 1}, {1, 0, 0}), 0.0, hit));
  EXPECT_NEAR(hit.t, 4.5, 1e-12);
  hit.t = 100;  // from above onto the cap
  ASSERT_TRUE(pole.intersect(Ray({5, 0.1, 10}, {0, 0, -1}), 0.0, hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  EXPECT_NEAR(hit.normal.z(), 1.0, 1e-12);
  const auto canopy = Primitive::ellipsoid({0, 20, 5}, {2, 3, 1.5}, kFoliage);
  hit.t = 100;
  ASSERT_TRUE(canopy.intersect(Ray({0, 0, 5}, {0, 1, 0}), 0.0, hit));
  EXPECT_NEAR(hit.t, 17.0, 1e-9);
  hit.t = 100;
  ASSERT_TRUE(canopy.intersect(Ray({0, 20, 0}, {0, 0, 1}), 0.0, hit));
  EXPECT_NEAR(hit.t, 3.5, 1e-9);
  // Surface distances.
  EXPECT_NEAR(pole.surfaceDistance({5, 2, 3}), 1.5, 1e-12);
  EXPECT_NEAR(Primitive::box({0, 0, 0}, {1, 1, 1}, 0.3, 0).surfaceDistance({0, 0, 0.5}), 0.5, 1e-12);
}

TEST(RayCasting, FlatAndSlopedTerrain) {
  Terrain flat({-100, -100}, 2.0, 100, 100, 1.0);
  Hit hit;
  hit.t = 200;
  const double el = -10.0 * M_PI / 180.0;
  const Vector3d d(std::cos(el), 0.3 * std::cos(el), std::sin(el));
  ASSERT_TRUE(flat.intersect(Ray({0, 0, 1.5}, d.normalized()), 0.0, hit));
  EXPECT_NEAR(hit.t * d.normalized().z(), -1.5, 1e-9);
  EXPECT_NEAR(hit.normal.z(), 1.0, 1e-12);
  hit.t = 200;  // upward ray: no ground
  EXPECT_FALSE(flat.intersect(Ray({0, 0, 1.5}, Vector3d(1, 0, 0.1).normalized()), 0.0, hit));
  // Generated terrain: the hit point lies on height(x, y).
  std::mt19937_64 rng(3);
  TerrainParams tp;
  tp.amplitude = 3.0;
  tp.wavelength = 80.0;
  const Terrain hills = Terrain::generate({-150, -150}, {150, 150}, tp, rng);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int k = 0; k < 2000; ++k) {
    const double x = 60 * u(rng), y = 60 * u(rng);
    const Vector3d o(x, y, hills.height(x, y) + 2.0);
    const Vector3d dir = Vector3d(u(rng), u(rng), -0.05 - 0.3 * std::abs(u(rng))).normalized();
    Hit h;
    h.t = 300;
    if (!hills.intersect(Ray(o, dir), 0.0, h)) continue;
    ++hits;
    const Vector3d p = o + h.t * dir;
    ASSERT_NEAR(p.z(), hills.height(p.x(), p.y()), 1e-6) << "ray " << k;
  }
  EXPECT_GT(hits, 1800);
}

TEST(RayCasting, BvhMatchesBruteForce) {
  WorldParams wp;
  wp.blocks_x = 2;
  wp.blocks_y = 2;
  const World world = generateWorld(wp, 5);
  const auto& prims = world.objects().primitives();
  ASSERT_GT(prims.size(), 100u);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 3000; ++k) {
    const Ray ray(Vector3d(80 * u(rng), 80 * u(rng), 1.5 + std::abs(u(rng))),
                  Vector3d(u(rng), u(rng), 0.3 * u(rng)).normalized());
    Hit a, b;
    a.t = b.t = 120.0;
    const bool ha = world.objects().intersect(ray, 1e-6, a);
    bool hb = false;
    for (const auto& p : prims) hb |= p.intersect(ray, 1e-6, b);
    ASSERT_EQ(ha, hb) << "ray " << k;
    if (ha) { ASSERT_NEAR(a.t, b.t, 1e-9) << "ray " << k; }
  }
}
