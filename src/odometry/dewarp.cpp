#include "cosmo/odometry/dewarp.hpp"

#include <algorithm>
#include <cmath>

namespace cosmo::odometry {
namespace {
constexpr int kBins = 2048;

/// Signed stamp arithmetic: stamp + seconds, clamped at 0.
StampNs offsetStamp(StampNs stamp, double seconds) {
  const long double t = static_cast<long double>(stamp) + static_cast<long double>(seconds) * 1e9L;
  return t <= 0 ? 0 : static_cast<StampNs>(std::llround(static_cast<double>(t)));
}

/// std::lround(x) for a bin position x in [0, 2^31) (half away from zero), inline instead of a libm call per
/// point: x - trunc(x) is exact, so the result is lround's bit for bit. Branch-free (the fraction is random
/// per point); NaN gives bin 0.
int roundBin(double x) {
  x = x >= 0.0 ? x : 0.0;
  const int b = static_cast<int>(x);
  return b + static_cast<int>(x - static_cast<double>(b) >= 0.5);
}
}  // namespace

Scan dewarp(const Scan& scan, const std::function<Pose3(StampNs)>& sensor_pose_at) {
  Scan out = scan;
  if (!scan.hasTime() || scan.empty()) return out;
  float tmin = std::numeric_limits<float>::infinity(), tmax = -tmin;
  for (float t : scan.time)
    if (std::isfinite(t)) {
      tmin = std::min(tmin, t);
      tmax = std::max(tmax, t);
    }
  if (!std::isfinite(tmin)) {
    std::fill(out.time.begin(), out.time.end(), 0.0f);
    return out;
  }
  const Pose3 ref_inv = sensor_pose_at(scan.stamp).inverse();
  const double span = static_cast<double>(tmax) - static_cast<double>(tmin);
  std::vector<Pose3, Eigen::aligned_allocator<Pose3>> cache(kBins + 1);
  std::vector<std::uint8_t> have(kBins + 1, 0);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const float t = scan.time[i];
    if (!std::isfinite(t)) continue;
    const int b = span > 0.0 ? roundBin((t - tmin) / span * kBins) : 0;
    if (!have[b]) {
      const double tb = span > 0.0 ? tmin + span * static_cast<double>(b) / kBins : tmin;
      cache[b] = ref_inv * sensor_pose_at(offsetStamp(scan.stamp, tb));
      have[b] = 1;
    }
    out.points[i] = (cache[b] * scan.points[i].cast<double>()).cast<float>();
  }
  std::fill(out.time.begin(), out.time.end(), 0.0f);
  return out;
}

void deskewConstantVelocity(const std::vector<Eigen::Vector3d>& points, const std::vector<float>& times,
                            const Pose3& delta, double period, std::vector<Eigen::Vector3d>& out) {
  out.resize(points.size());
  if (times.size() != points.size() || !(period > 0.0)) {
    std::copy(points.begin(), points.end(), out.begin());
    return;
  }
  const Vector6 xi = logSE3(delta);
  // Bin the fraction s = t / period to 1/256 and cache the poses: [-1.5, 1.5] holds a sweep stamped at its end
  // (s in [-1, 0]) or at its start ([0, 1]) with room for a late or early stamp.
  constexpr int kSteps = 256;
  constexpr double kLo = -1.5, kHi = 1.5;
  const int nb = static_cast<int>((kHi - kLo) * kSteps) + 1;
  std::vector<Pose3, Eigen::aligned_allocator<Pose3>> cache(nb);
  std::vector<std::uint8_t> have(nb, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double s = std::clamp(static_cast<double>(times[i]) / period, kLo, kHi);
    const int b = roundBin((s - kLo) * kSteps);
    if (!have[b]) {
      cache[b] = expSE3((kLo + static_cast<double>(b) / kSteps) * xi);
      have[b] = 1;
    }
    out[i] = cache[b] * points[i];
  }
}

}  // namespace cosmo::odometry
