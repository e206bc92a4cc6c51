#pragma once
// A small procedural world for place-recognition tests: random pillars and walls on flat ground, "scanned"
// from a planar pose without occlusion. Deterministic for a given seed.
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "cosmo/common/scan.hpp"

namespace cosmo::test_support {

class PillarScene {
 public:
  explicit PillarScene(unsigned seed, double half_size = 200.0, int pillars = 400) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> pos(-half_size, half_size), height(1.0, 15.0), radius(0.5, 3.0),
        angle(0.0, 2.0 * M_PI), len(5.0, 30.0);
    for (int i = 0; i < pillars; ++i) {
      const double cx = pos(rng), cy = pos(rng), h = height(rng), r = radius(rng);
      for (double z = 0.0; z <= h; z += 0.5)
        for (int k = 0; k < 12; ++k) {
          const double a = 2.0 * M_PI * k / 12.0;
          points_.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a), z);
        }
      if (i % 4 == 0) {  // a wall next to every fourth pillar
        const double a = angle(rng), l = len(rng), wh = height(rng) * 0.5;
        for (double s = 0.0; s <= l; s += 0.5)
          for (double z = 0.0; z <= wh; z += 0.5) points_.emplace_back(cx + s * std::cos(a), cy + s * std::sin(a), z);
      }
    }
  }

  /// Scan from a sensor at (x, y) with heading yaw, `sensor_z` above the ground, points within `range`.
  Scan scanAt(double x, double y, double yaw, double sensor_z = 1.8, double range = 90.0) const {
    Scan scan;
    const Eigen::Matrix3d R_ws = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d t(x, y, sensor_z);
    for (const auto& p : points_) {
      const Eigen::Vector3d d = p - t;
      if (d.head<2>().squaredNorm() > range * range) continue;
      scan.points.push_back((R_ws.transpose() * d).cast<float>());
    }
    // Flat ground as the lower beams of a spinning LiDAR see it: circles around the sensor (elevations -25 to
    // -3 degrees, 0.5 degree azimuth steps), so the ground itself does not depend on the heading.
    for (int e = 3; e <= 25; ++e) {
      const double r = sensor_z / std::tan(e * M_PI / 180.0);
      for (int k = 0; k < 720; ++k) {
        const double a = k * M_PI / 360.0;
        scan.points.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                                 static_cast<float>(-sensor_z));
      }
    }
    return scan;
  }

 private:
  std::vector<Eigen::Vector3d> points_;
};

/// The scan as seen by the same sensor turned by +yaw about z (points turned by -yaw).
inline Scan turnSensor(const Scan& scan, double yaw) {
  Scan out = scan;
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(-yaw), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : out.points) p = R * p;
  return out;
}

}  // namespace cosmo::test_support
