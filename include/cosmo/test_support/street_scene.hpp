#pragma once
// A small analytic world (ground, street walls, boxes, poles) and a spinning multi-beam LiDAR ray-cast into
// it, with motion during the sweep: test and benchmark input for the odometry with exact ground truth.
// Deterministic: no randomness unless a seeded RNG is given.
#include <functional>
#include <random>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"

namespace cosmo::test_support {

struct SyntheticLidar {
  int rings = 64;               ///< beams
  int columns = 1024;           ///< azimuth steps per sweep
  double fov_up_deg = 16.6;     ///< highest beam elevation
  double fov_down_deg = -16.6;  ///< lowest beam elevation
  double max_range = 120.0;     ///< m; no return beyond
  double period = 0.1;          ///< s per sweep
  double range_noise = 0.0;     ///< m, Gaussian sigma (needs an RNG)
};

struct SyntheticScene {
  struct Box {
    Eigen::Vector3d min, max;
  };
  struct Pole {
    Eigen::Vector2d centre;
    double radius;
  };
  double ground_z = -1.8;  ///< ground plane height in the world frame
  std::vector<Box> boxes;
  std::vector<Pole> poles;

  /// A street 2*half_width wide along +x, length `length`, with walls of buildings (boxes of random-free
  /// deterministic widths and setbacks), parked boxes and poles every few metres.
  static SyntheticScene street(double length = 200.0, double half_width = 8.0);
  /// A featureless corridor along x: two infinite-looking walls, floor and ceiling, nothing else.
  static SyntheticScene corridor(double length = 400.0, double half_width = 2.0, double height = 3.0);

  /// Range along the ray (origin o, unit direction d) to the nearest surface, or +inf.
  double raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range) const;
};

/// One sweep stamped at its end (`stamp`); column c is measured at time -(columns - 1 - c) / columns *
/// period, when the sensor pose is `pose_at(time)` (world frame). Points in the sensor frame at that time
/// (i.e. distorted, as a real spinning LiDAR delivers them), with ring and time fields. Misses are dropped.
Scan simulateSweep(const SyntheticScene& scene, const SyntheticLidar& lidar, StampNs stamp,
                   const std::function<Pose3(double)>& pose_at, std::mt19937_64* rng = nullptr);

}  // namespace cosmo::test_support
