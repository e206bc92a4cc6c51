#include "cosmo/registration/voxel_downsample.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace cosmo {

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                                             double min_range, double max_range) {
  std::vector<Eigen::Vector3f> out;
  if (points.empty() || !(voxel_size > 0.0)) return out;
  const double inv = 1.0 / voxel_size;
  const double min2 = min_range * min_range;
  const double max2 = max_range > 0.0 ? max_range * max_range : std::numeric_limits<double>::infinity();
  // Per-voxel sums in a hash map (slot per voxel in first-seen order), then the voxels emitted in key order:
  // deterministic without depending on the hash map's iteration order, and no sort over all points.
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of;
  slot_of.reserve(points.size() / 4 + 16);
  std::vector<std::uint64_t> keys;
  std::vector<Eigen::Vector3d> sums;
  std::vector<std::uint32_t> counts;
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
    const auto [it, inserted] = slot_of.try_emplace(key, static_cast<std::uint32_t>(keys.size()));
    if (inserted) {
      keys.push_back(key);
      sums.emplace_back(Eigen::Vector3d::Zero());
      counts.push_back(0);
    }
    sums[it->second] += p.cast<double>();
    ++counts[it->second];
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(keys.size());
  for (std::size_t v = 0; v < keys.size(); ++v) order[v] = {keys[v], static_cast<std::uint32_t>(v)};
  std::sort(order.begin(), order.end());
  out.reserve(order.size());
  for (const auto& [key, v] : order) out.push_back((sums[v] / static_cast<double>(counts[v])).cast<float>());
  return out;
}

}  // namespace cosmo
