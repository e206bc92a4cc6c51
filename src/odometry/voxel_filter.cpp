#include "cosmo/odometry/voxel_filter.hpp"

#include <cmath>
#include <unordered_set>

#include "cosmo/common/voxel_key.hpp"

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
    const std::uint64_t k = packVoxelKey(voxelCoord(p.x(), inv), voxelCoord(p.y(), inv), voxelCoord(p.z(), inv));
    if (occupied.insert(k).second) kept.push_back(static_cast<std::uint32_t>(i));
  }
  return kept;
}

}  // namespace cosmo
