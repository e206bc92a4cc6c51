#include "cosmo/sim/scan_simulator.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "cosmo/sim/material.hpp"

namespace cosmo::sim {

namespace {
inline double uniform01(std::uint64_t& s) { return static_cast<double>(splitmix64(s) >> 11) * 0x1.0p-53; }
inline double gaussian(std::uint64_t& s) {
  const double u1 = std::max(uniform01(s), 1e-300), u2 = uniform01(s);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

/// A random direction of the beam's footprint: within `half_angle` of the beam axis `d`, uniform over the disc.
Eigen::Vector3d footprintDirection(const Eigen::Vector3d& d, double half_angle, std::uint64_t& rs) {
  const Eigen::Vector3d e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  const double rad = half_angle * std::sqrt(uniform01(rs)), phi = 2.0 * M_PI * uniform01(rs);
  return (d + rad * (std::cos(phi) * e1 + std::sin(phi) * e2)).normalized();
}

/// Canopies as a volume of leaves: a ray that enters one scatters after an exponential depth (mean free path
/// `mfp`) unless it leaves the canopy, or meets a trunk or another surface, first; then it goes on to what lies
/// behind. On a return inside a canopy the leaf faces a random way (`cos_inc`). False: the ray left every canopy
/// and met nothing.
bool throughCanopies(const World& world, const Ray& ray, double mfp, double max_range, std::uint64_t& rs, Hit& hit,
                     double& cos_inc) {
  for (int k = 0; k < 8 && hit.material == kFoliage; ++k) {
    const double depth = -mfp * std::log(std::max(uniform01(rs), 1e-300));
    Hit next;
    const bool more = world.intersect(ray, hit.t + 1e-4, max_range, next);
    const double leave = more ? std::min(hit.exit, next.t) : hit.exit;
    if (hit.t + depth < leave) {
      hit.t += depth;
      cos_inc = 0.2 + 0.8 * uniform01(rs);
      return true;
    }
    if (!more) return false;
    hit = next;
    cos_inc = std::abs(hit.normal.dot(ray.d));
  }
  return true;
}

/// Late detection of weak pulses: `walk` for a return at the detection limit (strength 1), falling linearly with
/// log10 of the strength to 0 at 1000.
double rangeWalk(double walk, double strength) {
  return walk * std::clamp(1.0 - std::log10(std::max(strength, 1e-12)) / 3.0, 0.0, 1.0);
}
}  // namespace

ScanSimulator::ScanSimulator(const World& world, LidarModel lidar) : world_(world), lidar_(std::move(lidar)) {
  const auto el = lidar_.elevations();
  dirs_.resize(lidar_.raysPerScan());
  for (int b = 0; b < lidar_.beams; ++b)
    for (int c = 0; c < lidar_.columns; ++c) {
      const double az = lidar_.azimuth(c);
      dirs_[static_cast<std::size_t>(b) * lidar_.columns + c] =
          Eigen::Vector3d(std::cos(el[b]) * std::cos(az), std::cos(el[b]) * std::sin(az), std::sin(el[b]));
    }
}

Scan ScanSimulator::simulate(const Trajectory& body, const Pose3& T_body_lidar, StampNs stamp,
                             std::uint64_t seed) const {
  if (body.empty()) throw std::invalid_argument("ScanSimulator: empty trajectory");
  std::vector<Pose3> poses(static_cast<std::size_t>(lidar_.columns));
  for (int c = 0; c < lidar_.columns; ++c) {
    const double dt = lidar_.columnTime(c);
    const StampNs t = stamp - static_cast<StampNs>(std::llround(-dt * 1e9));
    poses[c] = body.atClamped(t) * T_body_lidar;
  }
  return simulate(poses, stamp, seed);
}

std::vector<Eigen::Vector3d> ScanSimulator::castDirections(std::uint64_t seed) const {
  if (!(lidar_.beam_angle_sigma_deg > 0.0)) return dirs_;
  const auto el = lidar_.elevations();
  const double sigma = lidar_.beam_angle_sigma_deg * M_PI / 180.0;
  std::vector<Eigen::Vector3d> out(dirs_.size());
  for (int b = 0; b < lidar_.beams; ++b) {
    std::uint64_t s = seed ^ (0xA24BAED4963EE407ULL * static_cast<std::uint64_t>(b + 1));
    splitmix64(s);
    const double e = el[b] + sigma * gaussian(s), da = sigma * gaussian(s);
    const double ce = std::cos(e), se = std::sin(e), cd = std::cos(da), sd = std::sin(da);
    for (int c = 0; c < lidar_.columns; ++c) {
      const double az = lidar_.azimuth(c), ca = std::cos(az) * cd - std::sin(az) * sd,
                   sa = std::sin(az) * cd + std::cos(az) * sd;
      out[static_cast<std::size_t>(b) * lidar_.columns + c] = Eigen::Vector3d(ce * ca, ce * sa, se);
    }
  }
  return out;
}

Scan ScanSimulator::simulate(const std::vector<Pose3>& column_poses, StampNs stamp, std::uint64_t seed) const {
  const int B = lidar_.beams, C = lidar_.columns;
  if (static_cast<int>(column_poses.size()) != C)
    throw std::invalid_argument("ScanSimulator: expected one pose per column");
  const std::size_t n = lidar_.raysPerScan();
  std::vector<float> range(n, std::numeric_limits<float>::quiet_NaN());
  std::vector<float> intensity(n, 0.0f);
  std::uint64_t scan_key = seed ^ (stamp * 0xD1B54A32D192ED03ULL);
  const std::uint64_t scan_seed = splitmix64(scan_key);
  const auto& materials = materialTable();
  const LidarModel& L = lidar_;
  const std::vector<Eigen::Vector3d> cast =
      L.beam_angle_sigma_deg > 0.0 ? castDirections(seed) : std::vector<Eigen::Vector3d>{};
  const std::vector<Eigen::Vector3d>& cast_dirs = cast.empty() ? dirs_ : cast;
  const double half_divergence = 0.5e-3 * L.beam_divergence_mrad;
  const bool volume_foliage = L.foliage_mean_free_path > 0.0;

  tbb::parallel_for(tbb::blocked_range<int>(0, C, 16), [&](const tbb::blocked_range<int>& cols) {
    for (int c = cols.begin(); c != cols.end(); ++c) {
      const Pose3& T = column_poses[c];
      const Eigen::Matrix3d R = T.linear();
      const Eigen::Vector3d origin = T.translation();
      for (int b = 0; b < B; ++b) {
        const std::size_t idx = static_cast<std::size_t>(b) * C + c;
        std::uint64_t rs = scan_seed ^ (static_cast<std::uint64_t>(idx) * 0x9E3779B97F4A7C15ULL);
        splitmix64(rs);
        const Eigen::Vector3d axis = R * cast_dirs[idx];
        const Ray ray(origin, half_divergence > 0.0 ? footprintDirection(axis, half_divergence, rs) : axis);
        Hit hit;
        if (!world_.intersect(ray, 1e-6, L.max_range, hit)) continue;
        double cos_inc = std::abs(hit.normal.dot(ray.d));
        if (volume_foliage && !throughCanopies(world_, ray, L.foliage_mean_free_path, L.max_range, rs, hit, cos_inc))
          continue;
        if (cos_inc < L.grazing_cos) continue;
        const MaterialProps& m = materials[hit.material < kCount ? hit.material : 0];
        const double returns = L.material_losses ? m.return_prob : 1.0;
        if (uniform01(rs) > returns * (1.0 - L.dropout)) continue;
        // Detection probability falls off steeply around a range that grows with the returned signal.
        const double signal = std::max(1e-4, m.reflectivity * cos_inc);
        const double r50 = L.detection_range * std::sqrt(signal / 0.1);
        const double q = hit.t / r50;
        const double q2 = q * q, q4 = q2 * q2;
        if (uniform01(rs) > 1.0 / (1.0 + q4 * q4)) continue;
        double r = hit.t + (L.range_sigma + L.range_sigma_per_m * hit.t) * gaussian(rs);
        if (L.range_walk > 0.0) r += rangeWalk(L.range_walk, signal / 0.1 * std::pow(L.detection_range / hit.t, 2));
        if (!volume_foliage && m.depth_spread > 0.0f && L.foliage_spread > 0.0)
          r += L.foliage_spread * m.depth_spread * uniform01(rs);
        if (r < L.min_range || r > L.max_range) continue;
        range[idx] = static_cast<float>(r);
        intensity[idx] =
            static_cast<float>(std::min(L.intensity_scale * signal * (0.95 + 0.1 * uniform01(rs)), 65535.0));
      }
    }
  });

  Scan scan;
  scan.stamp = stamp;
  std::size_t valid = 0;
  for (float r : range) valid += std::isfinite(r) ? 1 : 0;
  scan.reserve(valid);
  for (int b = 0; b < B; ++b)
    for (int c = 0; c < C; ++c) {
      const std::size_t idx = static_cast<std::size_t>(b) * C + c;
      if (!std::isfinite(range[idx])) continue;
      scan.points.push_back((range[idx] * dirs_[idx]).cast<float>());
      scan.intensity.push_back(intensity[idx]);
      scan.time.push_back(static_cast<float>(L.columnTime(c)));
      scan.ring.push_back(static_cast<std::uint16_t>(b));
    }
  return scan;
}

}  // namespace cosmo::sim
