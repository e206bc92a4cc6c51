#pragma once
// The synthetic scenes of the tests and benchmarks: every one is a world of the simulator (cosmo::sim primitives
// in its BVH) swept by the simulator's own ScanSimulator, the engine that makes the synthetic trials. The scenes
// differ only in what they hold: an analytic street and a featureless corridor (odometry under motion, exact
// ground truth), a seeded field of pillars and walls (place recognition), a street corner of the simulated campus
// (benchmark input). The sensor is the simulator's Ouster model with its imperfections turned off, so that a test
// measures the code under test and not the sensor model; a test turns one on (range noise) where it wants it.
#include <cstdint>
#include <functional>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/sim/lidar_model.hpp"
#include "cosmo/sim/world.hpp"

namespace cosmo::test_support {

/// The simulator's OS1-64 (64 x 1024, +-16.6 deg, 10 Hz, 120 m) as an ideal sensor: no range noise, no beam
/// calibration error, no random dropout, no lost returns of the materials, no detection fall-off with range, no
/// grazing-angle cut: every ray that reaches a surface returns it. (Lost returns open gaps in the scan lines that
/// LOAM takes for edges: a featureless corridor then looks constrained along its axis.)
sim::LidarModel idealLidar();

/// A street 2 * half_width wide along +x from 0 to `length`: building blocks on both sides (deterministic widths,
/// setbacks and heights, alleys between them), parked cars and lamp posts along the kerbs, flat ground 1.8 m below
/// the world origin (z = -1.8).
sim::World streetWorld(double length = 200.0, double half_width = 8.0);
/// A featureless corridor along x: two long walls, a floor 1 m below the origin and a ceiling `height` above the
/// floor, nothing else (degenerate along x for scan matching).
sim::World corridorWorld(double length = 400.0, double half_width = 2.0, double height = 3.0);

/// One sweep stamped at its end (`stamp`): column c is fired at lidar.columnTime(c) (<= 0 s), when the sensor pose
/// in the world is `pose_at(that time)`. Points in the sensor frame at their own time (distorted, as a spinning
/// LiDAR delivers them), ring by ring (ring 0 the top beam), with intensity, time and ring. `noise_seed` keys the
/// simulator's per-ray draws (range noise when lidar.range_sigma > 0, the materials' lost returns).
Scan simulateSweep(const sim::World& world, const sim::LidarModel& lidar, StampNs stamp,
                   const std::function<Pose3(double)>& pose_at, std::uint64_t noise_seed = 0);

/// A field of `pillars` vertical pillars (0.5-3 m radius, 1-15 m high) in a square of +-half_size, a wall beside
/// every fourth one, on flat ground at z = 0. Deterministic for a given seed.
sim::World pillarWorld(unsigned seed, double half_size = 200.0, int pillars = 400);
/// A stationary sweep of an ideal 32-beam sensor (+-22.5 deg, 1024 columns) at (x, y), `sensor_z` above the
/// ground, heading `yaw`, keeping returns within `range`.
Scan scanAt(const sim::World& world, double x, double y, double yaw, double sensor_z = 1.8, double range = 90.0);
/// The scan as seen by the same sensor turned by +yaw about z (points turned by -yaw).
Scan turnSensor(const Scan& scan, double yaw);

/// A stationary sweep of an ideal `beams` x 1024 sensor (+-22.5 deg) 1.8 m above a street junction of the
/// simulated campus (the simulator's default world parameters, seed 1): a realistic, dense scan for timings.
Scan campusScan(int beams);

}  // namespace cosmo::test_support
