#include "cosmo/test_support/street_scene.hpp"

#include <cmath>
#include <limits>

namespace cosmo::test_support {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

double rayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const SyntheticScene::Box& b) {
  double t0 = 0.0, t1 = kInf;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (o[i] < b.min[i] || o[i] > b.max[i]) return kInf;
      continue;
    }
    double a = (b.min[i] - o[i]) / d[i], c = (b.max[i] - o[i]) / d[i];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
    if (t0 > t1) return kInf;
  }
  return t0 > 1e-6 ? t0 : kInf;
}

double rayPole(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const SyntheticScene::Pole& p) {
  const double ox = o.x() - p.centre.x(), oy = o.y() - p.centre.y();
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a < 1e-12) return kInf;
  const double b = 2.0 * (ox * d.x() + oy * d.y());
  const double c = ox * ox + oy * oy - p.radius * p.radius;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return kInf;
  const double t = (-b - std::sqrt(disc)) / (2.0 * a);
  return t > 1e-6 ? t : kInf;
}
}  // namespace

SyntheticScene SyntheticScene::street(double length, double half_width) {
  SyntheticScene s;
  // Buildings on both sides: blocks of varying width, depth and setback (deterministic pattern).
  for (int side : {-1, 1}) {
    double x = -40.0;
    int k = 0;
    while (x < length + 40.0) {
      const double w = 6.0 + 4.0 * std::abs(std::sin(1.7 * k + (side > 0 ? 0.3 : 1.1)));
      const double setback = 0.8 * std::abs(std::sin(2.3 * k + side));
      const double h = 4.0 + 6.0 * std::abs(std::cos(0.9 * k));
      const double y0 = side * (half_width + setback);
      const double y1 = side * (half_width + setback + 10.0);
      s.boxes.push_back(
          {Eigen::Vector3d(x, std::min(y0, y1), s.ground_z), Eigen::Vector3d(x + w, std::max(y0, y1), s.ground_z + h)});
      x += w + 1.0 + 2.0 * std::abs(std::sin(0.7 * k));  // alleys between blocks
      ++k;
    }
  }
  // Parked cars (boxes) and poles along the kerbs.
  for (int k = 0; k * 9.0 < length + 40.0; ++k) {
    const double x = -30.0 + 9.0 * k + 2.0 * std::sin(k);
    const int side = (k % 2) ? 1 : -1;
    const double y = side * (half_width - 1.5);
    s.boxes.push_back({Eigen::Vector3d(x, y - 0.9, s.ground_z), Eigen::Vector3d(x + 4.2, y + 0.9, s.ground_z + 1.5)});
    s.poles.push_back({Eigen::Vector2d(x + 6.0, -side * (half_width - 0.5)), 0.15});
  }
  return s;
}

SyntheticScene SyntheticScene::corridor(double length, double half_width, double height) {
  SyntheticScene s;
  s.ground_z = -1.0;
  s.boxes.push_back(
      {Eigen::Vector3d(-length, half_width, -5.0), Eigen::Vector3d(length, half_width + 1.0, height + 5.0)});
  s.boxes.push_back(
      {Eigen::Vector3d(-length, -half_width - 1.0, -5.0), Eigen::Vector3d(length, -half_width, height + 5.0)});
  s.boxes.push_back({Eigen::Vector3d(-length, -half_width - 1.0, s.ground_z + height),
                     Eigen::Vector3d(length, half_width + 1.0, s.ground_z + height + 1.0)});
  return s;
}

double SyntheticScene::raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range) const {
  double best = kInf;
  if (d.z() < -1e-9) {
    const double t = (ground_z - o.z()) / d.z();
    if (t > 0.0) best = t;
  }
  for (const auto& b : boxes) best = std::min(best, rayBox(o, d, b));
  for (const auto& p : poles) best = std::min(best, rayPole(o, d, p));
  return best <= max_range ? best : kInf;
}

Scan simulateSweep(const SyntheticScene& full_scene, const SyntheticLidar& lidar, StampNs stamp,
                   const std::function<Pose3(double)>& pose_at, std::mt19937_64* rng) {
  // Only the objects within reach of this sweep.
  SyntheticScene scene;
  scene.ground_z = full_scene.ground_z;
  const Eigen::Vector3d c0 = pose_at(0.0).translation();
  const double reach = lidar.max_range + 20.0;
  for (const auto& b : full_scene.boxes) {
    const Eigen::Vector3d closest = c0.cwiseMax(b.min).cwiseMin(b.max);
    if ((closest - c0).norm() < reach) scene.boxes.push_back(b);
  }
  for (const auto& p : full_scene.poles)
    if ((p.centre - c0.head<2>()).norm() < reach) scene.poles.push_back(p);
  Scan scan;
  scan.stamp = stamp;
  scan.reserve(static_cast<std::size_t>(lidar.rings) * lidar.columns);
  std::normal_distribution<double> noise(0.0, lidar.range_noise);
  std::vector<double> elev(lidar.rings);
  for (int r = 0; r < lidar.rings; ++r)
    elev[r] =
        (lidar.fov_down_deg + (lidar.fov_up_deg - lidar.fov_down_deg) * r / std::max(1, lidar.rings - 1)) * kPi / 180.0;
  // Column-major, as an Ouster delivers: all rings of a column share a time.
  for (int c = 0; c < lidar.columns; ++c) {
    const double t = -static_cast<double>(lidar.columns - 1 - c) / lidar.columns * lidar.period;
    const Pose3 T = pose_at(t);
    const double az = kPi - 2.0 * kPi * c / lidar.columns;  // clockwise from the back
    for (int r = 0; r < lidar.rings; ++r) {
      const Eigen::Vector3d dir_s(std::cos(elev[r]) * std::cos(az), std::cos(elev[r]) * std::sin(az),
                                  std::sin(elev[r]));
      const Eigen::Vector3d dir_w = T.linear() * dir_s;
      double range = scene.raycast(T.translation(), dir_w, lidar.max_range);
      if (!std::isfinite(range)) continue;
      if (rng && lidar.range_noise > 0.0) range += noise(*rng);
      scan.points.push_back((range * dir_s).cast<float>());
      scan.intensity.push_back(1.0f);
      scan.time.push_back(static_cast<float>(t));
      scan.ring.push_back(static_cast<std::uint16_t>(r));
    }
  }
  return scan;
}

}  // namespace cosmo::test_support
