// The LiDAR physics that make two scans of one place disagree by centimetres (LidarModel): canopies as a volume
// of leaves, late detection of weak returns (range walk), returns from anywhere in the beam's footprint. Each is
// checked on a small world whose surfaces are known: a tree canopy in front of a wall, walls near and far; and
// hedges (WorldParams::hedge_fraction), foliage added to a generated world without moving anything else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cosmo/sim/material.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/world_generator.hpp"

using namespace cosmo;
using namespace cosmo::sim;

namespace {
constexpr double kSensorHeight = 3.0;

/// Flat ground; a canopy (radius 2 m) 10 m east of the sensor in front of a wall at 20 m; a wall 60 m west.
World testWorld() {
  Terrain ground(Eigen::Vector2d(-80, -80), 4.0, 40, 40, 0.5);
  std::vector<Primitive> prims;
  prims.push_back(Primitive::ellipsoid({10.0, 0.0, kSensorHeight}, {2.0, 2.0, 2.0}, kFoliage));
  prims.push_back(Primitive::box({20.5, 0.0, 5.0}, {0.5, 20.0, 5.0}, 0.0, kConcrete));
  prims.push_back(Primitive::box({-60.5, 0.0, 5.0}, {0.5, 30.0, 5.0}, 0.0, kConcrete));
  return World(std::move(ground), std::move(prims));
}

/// A noise-free sensor (no range noise, no dropouts) at the sensor height, looking along +x.
LidarModel exactLidar() {
  LidarModel l = LidarModel::os1_64();
  l.range_sigma = 0.0;
  l.dropout = 0.0;
  l.foliage_spread = 0.0;
  return l;
}

Scan scanOnce(const World& world, const LidarModel& lidar, StampNs stamp, std::uint64_t seed) {
  const ScanSimulator sim(world, lidar);
  Pose3 pose = Pose3::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, kSensorHeight);
  return sim.simulate(std::vector<Pose3>(static_cast<std::size_t>(lidar.columns), pose), stamp, seed);
}

/// Per point in the canopy's direction (within its angular radius): range minus where the beam's axis enters it.
std::vector<double> depthsBehindCanopySurface(const Scan& scan) {
  const Primitive canopy = Primitive::ellipsoid({10.0, 0.0, kSensorHeight}, {2.0, 2.0, 2.0}, kFoliage);
  std::vector<double> depths;
  for (const auto& p : scan.points) {
    const Eigen::Vector3d d = p.cast<double>().normalized();
    if (std::abs(d.z()) > 0.14) continue;  // steeper rays could meet the ground behind the canopy
    Hit hit;
    hit.t = 1e9;
    if (!canopy.intersect(Ray(Eigen::Vector3d(0, 0, kSensorHeight), d), 1e-6, hit)) continue;
    depths.push_back(p.cast<double>().norm() - hit.t);
  }
  return depths;
}
}  // namespace

TEST(SensorPhysics, ACanopyReturnsFromInsideItsVolumeAndLetsSomeRaysThroughDeterministically) {
  const World world = testWorld();
  const std::vector<double> surface = depthsBehindCanopySurface(scanOnce(world, exactLidar(), 1000000000, 5));
  ASSERT_GT(surface.size(), 100u);
  for (double d : surface) EXPECT_NEAR(d, 0.0, 1e-3) << "the ideal sensor returns from the canopy's surface";

  LidarModel lidar = exactLidar();
  lidar.foliage_mean_free_path = 0.7;
  const Scan scan = scanOnce(world, lidar, 1000000000, 5);
  const std::vector<double> depths = depthsBehindCanopySurface(scan);
  ASSERT_GT(depths.size(), 100u);
  std::vector<double> inside;
  int through = 0;
  for (double d : depths) {
    EXPECT_GT(d, -1e-3);
    if (d < 4.0 + 1e-3)
      inside.push_back(d);  // within the canopy (its diameter); beyond: the wall behind it
    else
      ++through;
  }
  ASSERT_GT(inside.size(), 50u);
  double mean = 0.0;
  for (double d : inside) mean += d / static_cast<double>(inside.size());
  const double deepest = *std::max_element(inside.begin(), inside.end());
  // Exponential depths of mean 0.7 m, cut by the canopy's chord: a spread of metres, not a surface.
  EXPECT_GT(mean, 0.35);
  EXPECT_LT(mean, 0.8);
  EXPECT_GT(deepest, 1.5);
  EXPECT_GT(through, 0) << "rays through the canopy's gaps reach the wall behind it";

  // Deterministic by seed and stamp; another scan of the same canopy scatters differently.
  const Scan again = scanOnce(world, lidar, 1000000000, 5);
  ASSERT_EQ(again.points.size(), scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) ASSERT_EQ(again.points[i], scan.points[i]);
  const std::vector<double> other = depthsBehindCanopySurface(scanOnce(world, lidar, 1100000000, 5));
  EXPECT_NE(other, depths);
}

TEST(SensorPhysics, RangeWalkMakesWeakReturnsLongerThanStrongOnes) {
  const World world = testWorld();
  LidarModel lidar = exactLidar();
  lidar.range_walk = 0.08;
  const Scan scan = scanOnce(world, lidar, 1000000000, 5);
  // Horizontal-ish points on the near (east, 20 m, strong; beside the canopy) and the far (west, 60 m, weak) wall.
  std::vector<double> near_bias, far_bias;
  for (const auto& pf : scan.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    if (std::abs(p.z()) > 2.0) continue;
    if (p.x() > 19.0 && std::abs(p.y()) > 6.0 && std::abs(p.y()) < 9.0)
      near_bias.push_back(p.norm() - 20.0 * p.norm() / p.x());
    if (std::abs(p.y()) > 3.0) continue;
    if (p.x() < -59.0) far_bias.push_back(p.norm() - 60.0 * p.norm() / -p.x());
  }
  ASSERT_GT(near_bias.size(), 10u);
  ASSERT_GT(far_bias.size(), 10u);
  std::nth_element(near_bias.begin(), near_bias.begin() + near_bias.size() / 2, near_bias.end());
  std::nth_element(far_bias.begin(), far_bias.begin() + far_bias.size() / 2, far_bias.end());
  const double near_med = near_bias[near_bias.size() / 2], far_med = far_bias[far_bias.size() / 2];
  EXPECT_GE(near_med, 0.0);
  EXPECT_GT(far_med, near_med + 0.01) << "a weaker return is detected later";
  EXPECT_LE(far_med, 0.08 + 1e-9);
}

TEST(SensorPhysics, BeamFootprintSpreadsOnlyObliqueSurfacesAndBleedsAtEdges) {
  const World world = testWorld();
  LidarModel lidar = exactLidar();
  lidar.beam_divergence_mrad = 3.0;
  const Scan scan = scanOnce(world, lidar, 1000000000, 5);
  // On the east wall at normal incidence (20 m: footprint 6 cm) the range error stays within mm; on the ground
  // (oblique, 10.5-14 m: the lowest beam reaches it at 10 m) ranges spread by centimetres around the axis' hit.
  double wall_max = 0.0, ground_max = 0.0;
  for (const auto& pf : scan.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const Eigen::Vector3d d = p.normalized();
    if (p.x() > 19.0 && std::abs(p.y()) < 1.0 && std::abs(p.z()) < 1.0)
      wall_max = std::max(wall_max, std::abs(p.norm() - 20.0 / d.x()));
    if (p.z() < -kSensorHeight + 0.5 && p.head<2>().norm() < 14.0 && p.head<2>().norm() > 10.5)
      ground_max = std::max(ground_max, std::abs(p.norm() - kSensorHeight / -d.z()));
  }
  EXPECT_LT(wall_max, 0.003);
  EXPECT_GT(ground_max, 0.02);
  EXPECT_LT(ground_max, 0.3);
}

TEST(SensorPhysics, HedgesAreFoliageBoxesAddedWithoutChangingTheRestOfTheWorld) {
  WorldParams wp;
  wp.blocks_x = 2;
  wp.blocks_y = 2;
  wp.block_min = 50;
  wp.block_max = 60;
  wp.outer_ring = 30;
  wp.terrain_margin = 60;
  const WorldLayout plain = generateLayout(wp, 3);
  const std::string key = wp.describe();
  wp.hedge_fraction = 0.5;
  EXPECT_NE(wp.describe(), key);  // the cache key follows the hedges
  const WorldLayout hedged = generateLayout(wp, 3);
  std::vector<Primitive> others;
  std::size_t hedges = 0;
  for (const Primitive& p : hedged.fixed) {
    if (p.kind == Primitive::Kind::Box && p.material == kFoliage) {
      ++hedges;
      EXPECT_NEAR(2.0 * p.half.y(), 1.0, 1e-9);  // 1 m thick
    } else {
      others.push_back(p);
    }
  }
  EXPECT_GT(hedges, 10u);
  // Every other object is where it was without hedges.
  ASSERT_EQ(others.size(), plain.fixed.size());
  for (std::size_t i = 0; i < others.size(); ++i) {
    EXPECT_EQ(others[i].center, plain.fixed[i].center);
    EXPECT_EQ(others[i].half, plain.fixed[i].half);
  }
  EXPECT_EQ(hedged.canopies.size(), plain.canopies.size());
  EXPECT_EQ(hedged.cars.size(), plain.cars.size());
}
