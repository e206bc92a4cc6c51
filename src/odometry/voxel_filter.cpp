#include "cosmo/odometry/voxel_filter.hpp"

#include <cmath>

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
  // Occupied voxels in a flat open-addressing set (linear probing, at most half full): keys use 63 bits, so
  // all-ones marks an empty slot. About 5x faster than std::unordered_set (one allocation per insert).
  constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  int bits = 4;
  while ((std::size_t{1} << bits) < 2 * points.size()) ++bits;
  const std::size_t mask = (std::size_t{1} << bits) - 1;
  std::vector<std::uint64_t> slots(mask + 1, kEmpty);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    if (!p.allFinite()) continue;
    // 21 bits per axis (+-2^20 voxels): wraps only beyond ~400 km at 0.4 m, harmless for a local map.
    const std::uint64_t k = packVoxelKey(voxelCoord(p.x(), inv), voxelCoord(p.y(), inv), voxelCoord(p.z(), inv));
    std::size_t h = static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> (64 - bits));
    while (slots[h] != kEmpty && slots[h] != k) h = (h + 1) & mask;
    if (slots[h] == kEmpty) {
      slots[h] = k;
      kept.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return kept;
}

}  // namespace cosmo
