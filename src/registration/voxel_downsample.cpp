#include "cosmo/registration/voxel_downsample.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace cosmo {

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                                             double min_range, double max_range) {
  std::vector<Eigen::Vector3f> out;
  if (points.empty() || !(voxel_size > 0.0)) return out;
  const double inv = 1.0 / voxel_size;
  const double min2 = min_range * min_range;
  const double max2 = max_range > 0.0 ? max_range * max_range : std::numeric_limits<double>::infinity();
  // (key, index) pairs sorted by key: a deterministic grouping without hash-map iteration order.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(points.size());
  constexpr std::int64_t kOffset = 1 << 20;  // 21 bits per axis: +-1e6 voxels
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    if (!p.allFinite()) continue;
    const double r2 = p.cast<double>().squaredNorm();
    if (r2 < min2 || r2 > max2) continue;
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() * inv)) + kOffset;
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() * inv)) + kOffset;
    const auto iz = static_cast<std::int64_t>(std::floor(p.z() * inv)) + kOffset;
    if (ix < 0 || iy < 0 || iz < 0 || ix >= 2 * kOffset || iy >= 2 * kOffset || iz >= 2 * kOffset) continue;
    const std::uint64_t key = (static_cast<std::uint64_t>(ix) << 42) | (static_cast<std::uint64_t>(iy) << 21) |
                              static_cast<std::uint64_t>(iz);
    keyed.emplace_back(key, static_cast<std::uint32_t>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t b = 0; b < keyed.size();) {
    std::size_t e = b;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (e < keyed.size() && keyed[e].first == keyed[b].first) sum += points[keyed[e++].second].cast<double>();
    out.push_back((sum / static_cast<double>(e - b)).cast<float>());
    b = e;
  }
  return out;
}

}  // namespace cosmo
