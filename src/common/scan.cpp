#include "cosmo/common/scan.hpp"

namespace cosmo {

Scan removeInvalidPoints(const Scan& scan, float min_range) {
  Scan out;
  out.stamp = scan.stamp;
  out.reserve(scan.size());
  const float min_sq = min_range * min_range;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3f& p = scan.points[i];
    if (!p.allFinite() || p.squaredNorm() < min_sq) continue;
    out.points.push_back(p);
    if (scan.hasIntensity()) out.intensity.push_back(scan.intensity[i]);
    if (scan.hasTime()) out.time.push_back(scan.time[i]);
    if (scan.hasRing()) out.ring.push_back(scan.ring[i]);
  }
  return out;
}

}  // namespace cosmo
