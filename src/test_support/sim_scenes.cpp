#include "cosmo/test_support/sim_scenes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cosmo/sim/material.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/world_generator.hpp"

namespace cosmo::test_support {
namespace {

using sim::Primitive;

/// An axis-aligned box from its corners.
Primitive boxBetween(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::uint8_t material) {
  return Primitive::box(0.5 * (lo + hi), 0.5 * (hi - lo), 0.0, material);
}

/// Flat ground: the top face of a 1 m thick slab at height `z` over [x0, x1] x [y0, y1].
Primitive ground(double x0, double x1, double y0, double y1, double z) {
  return boxBetween({x0, y0, z - 1.0}, {x1, y1, z}, sim::kAsphalt);
}

Pose3 planarPose(double x, double y, double z, double yaw) {
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Scan stationarySweep(const sim::World& world, const sim::LidarModel& lidar, const Pose3& pose) {
  return sim::ScanSimulator(world, lidar).simulate(std::vector<Pose3>(lidar.columns, pose), 0, 0);
}

}  // namespace

sim::LidarModel idealLidar() {
  sim::LidarModel m = sim::LidarModel::os1_64();
  m.name = "ideal_os1_64";
  m.min_range = 0.0;
  m.range_sigma = 0.0;
  m.grazing_cos = 0.0;
  m.detection_range = 1e9;
  m.dropout = 0.0;
  m.intensity_scale = 1.0;
  m.foliage_spread = 0.0;
  m.material_losses = false;
  return m;
}

sim::World streetWorld(double length, double half_width) {
  const double ground_z = -1.8;
  std::vector<Primitive> objects;
  objects.push_back(ground(-160.0, length + 160.0, -160.0, 160.0, ground_z));
  // Buildings on both sides: blocks of varying width, depth and setback (a deterministic pattern).
  for (int side : {-1, 1}) {
    double x = -40.0;
    int k = 0;
    while (x < length + 40.0) {
      const double w = 6.0 + 4.0 * std::abs(std::sin(1.7 * k + (side > 0 ? 0.3 : 1.1)));
      const double setback = 0.8 * std::abs(std::sin(2.3 * k + side));
      const double h = 4.0 + 6.0 * std::abs(std::cos(0.9 * k));
      const double y0 = side * (half_width + setback), y1 = side * (half_width + setback + 10.0);
      objects.push_back(
          boxBetween({x, std::min(y0, y1), ground_z}, {x + w, std::max(y0, y1), ground_z + h}, sim::kConcrete));
      x += w + 1.0 + 2.0 * std::abs(std::sin(0.7 * k));  // alleys between blocks
      ++k;
    }
  }
  // Parked cars and lamp posts along the kerbs.
  for (int k = 0; k * 9.0 < length + 40.0; ++k) {
    const double x = -30.0 + 9.0 * k + 2.0 * std::sin(k);
    const int side = (k % 2) ? 1 : -1;
    const double y = side * (half_width - 1.5);
    objects.push_back(boxBetween({x, y - 0.9, ground_z}, {x + 4.2, y + 0.9, ground_z + 1.5}, sim::kConcrete));
    objects.push_back(
        Primitive::cylinder(x + 6.0, -side * (half_width - 0.5), ground_z, ground_z + 8.0, 0.15, sim::kMetal));
  }
  return sim::World({}, std::move(objects));
}

sim::World corridorWorld(double length, double half_width, double height) {
  const double floor_z = -1.0;
  std::vector<Primitive> objects;
  objects.push_back(ground(-length, length, -half_width - 1.0, half_width + 1.0, floor_z));
  objects.push_back(boxBetween({-length, half_width, -5.0}, {length, half_width + 1.0, height + 5.0}, sim::kWall));
  objects.push_back(boxBetween({-length, -half_width - 1.0, -5.0}, {length, -half_width, height + 5.0}, sim::kWall));
  objects.push_back(boxBetween({-length, -half_width - 1.0, floor_z + height},
                               {length, half_width + 1.0, floor_z + height + 1.0}, sim::kWall));
  return sim::World({}, std::move(objects));
}

Scan simulateSweep(const sim::World& world, const sim::LidarModel& lidar, StampNs stamp,
                   const std::function<Pose3(double)>& pose_at, std::uint64_t noise_seed) {
  std::vector<Pose3> column_poses(static_cast<std::size_t>(lidar.columns));
  for (int c = 0; c < lidar.columns; ++c) column_poses[c] = pose_at(lidar.columnTime(c));
  return sim::ScanSimulator(world, lidar).simulate(column_poses, stamp, noise_seed);
}

sim::World pillarWorld(unsigned seed, double half_size, int pillars) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-half_size, half_size), height(1.0, 15.0), radius(0.5, 3.0),
      angle(0.0, 2.0 * M_PI), len(5.0, 30.0);
  std::vector<Primitive> objects;
  objects.push_back(ground(-half_size - 100.0, half_size + 100.0, -half_size - 100.0, half_size + 100.0, 0.0));
  for (int i = 0; i < pillars; ++i) {
    const double cx = pos(rng), cy = pos(rng), h = height(rng), r = radius(rng);
    objects.push_back(Primitive::cylinder(cx, cy, 0.0, h, r, sim::kConcrete));
    if (i % 4 == 0) {  // a wall next to every fourth pillar
      const double a = angle(rng), l = len(rng), wh = height(rng) * 0.5;
      objects.push_back(Primitive::box({cx + 0.5 * l * std::cos(a), cy + 0.5 * l * std::sin(a), 0.5 * wh},
                                       {0.5 * l, 0.15, 0.5 * wh}, a, sim::kWall));
    }
  }
  return sim::World({}, std::move(objects));
}

Scan scanAt(const sim::World& world, double x, double y, double yaw, double sensor_z, double range) {
  sim::LidarModel lidar = idealLidar();
  lidar.beams = 32;
  lidar.fov_up_deg = 22.5;
  lidar.fov_down_deg = -22.5;
  lidar.max_range = range;
  return stationarySweep(world, lidar, planarPose(x, y, sensor_z, yaw));
}

Scan turnSensor(const Scan& scan, double yaw) {
  Scan out = scan;
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(-yaw), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : out.points) p = R * p;
  return out;
}

Scan campusScan(int beams) {
  const sim::World world = sim::generateWorld(sim::WorldParams{}, 1);
  const Eigen::Vector2d junction = world.network().nodes[world.network().nodes.size() / 2];
  sim::LidarModel lidar = idealLidar();
  lidar.beams = beams;
  lidar.fov_up_deg = 22.5;
  lidar.fov_down_deg = -22.5;
  const double z = world.terrain().height(junction.x(), junction.y()) + 1.8;
  return stationarySweep(world, lidar, planarPose(junction.x(), junction.y(), z, 0.0));
}

}  // namespace cosmo::test_support
