#include "cosmo/odometry/voxel_filter.hpp"

#include <cmath>
#include <unordered_set>

namespace cosmo {

std::vector<std::uint32_t> voxelFilterIndices(const std::vector<Eigen::Vector3d>& points, double voxel_size) {
  std::vector<std::uint32_t> kept;
  kept.reserve(points.size());
  if (!(voxel_size > 0.0)) {
    for (std::size_t i = 0; i < points.size(); ++i) kept.push_back(static_cast<std::uint32_t>(i));
    return kept;
  }
  const double inv = 1.0 / voxel_size;
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(points.size() * 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    if (!p.allFinite()) continue;
    // 21 bits per axis (+-2^20 voxels): wraps only beyond ~400 km at 0.4 m, harmless for a local map.
    const auto key = [&](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v * inv)) & 0x1FFFFF); };
    const std::uint64_t k = key(p.x()) | (key(p.y()) << 21) | (key(p.z()) << 42);
    if (occupied.insert(k).second) kept.push_back(static_cast<std::uint32_t>(i));
  }
  return kept;
}

}  // namespace cosmo
