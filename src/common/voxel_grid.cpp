#include "cosmo/common/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "cosmo/common/voxel_key.hpp"
#include "cosmo/common/radix_sort.hpp"

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

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                                             double min_range, double max_range) {
  std::vector<Eigen::Vector3f> out;
  if (points.empty() || !(voxel_size > 0.0)) return out;
  const double inv = 1.0 / voxel_size;
  const double min2 = min_range * min_range;
  const double max2 = max_range > 0.0 ? max_range * max_range : std::numeric_limits<double>::infinity();
  // Per-voxel sums in an open-addressing hash table (linear probing, power-of-two size, slot per voxel in
  // first-seen order), then the voxels emitted in key order: deterministic without depending on the table's
  // layout, and no sort over all points.
  // Scan-ordered input mostly repeats the previous point's voxel: that one is checked first.
  constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t capacity = 1024;
  while (capacity < points.size() / 2) capacity *= 2;
  std::vector<std::uint64_t> table_key(capacity, kEmpty);
  std::vector<std::uint32_t> table_slot(capacity, 0);
  std::uint64_t mask = capacity - 1;
  auto probe = [&](std::uint64_t key) {
    std::uint64_t h = (key * 0x9E3779B97F4A7C15ull) >> 20;
    while (table_key[h & mask] != kEmpty && table_key[h & mask] != key) ++h;
    return static_cast<std::size_t>(h & mask);
  };
  std::uint64_t last_key = kEmpty;
  std::uint32_t last_slot = 0;
  std::vector<std::uint64_t> keys;
  std::vector<Eigen::Vector3d> sums;
  std::vector<std::uint32_t> counts;
  // The current voxel's sum and count stay in registers while consecutive points fall into it (the same
  // additions in the same order as through memory, without a store-to-load dependency per point).
  Eigen::Vector3d run_sum = Eigen::Vector3d::Zero();
  std::uint32_t run_count = 0;
  auto flushRun = [&]() {
    if (last_key == kEmpty) return;
    sums[last_slot] = run_sum;
    counts[last_slot] = run_count;
  };
  // In batches: the keys of the next kBatch points first (kEmpty = point skipped), with their table slots
  // prefetched, then the points summed in order (the table's random accesses overlap instead of waiting in turn).
  constexpr std::size_t kBatch = 32;
  std::uint64_t batch_key[kBatch];
  for (std::size_t i0 = 0; i0 < points.size(); i0 += kBatch) {
    const std::size_t len = std::min(kBatch, points.size() - i0);
    for (std::size_t b = 0; b < len; ++b) {
      const Eigen::Vector3f& p = points[i0 + b];
      batch_key[b] = kEmpty;
      if (!p.allFinite()) continue;
      const double r2 = p.cast<double>().squaredNorm();
      if (r2 < min2 || r2 > max2) continue;
      const std::int64_t ix = voxelCoord(p.x(), inv), iy = voxelCoord(p.y(), inv), iz = voxelCoord(p.z(), inv);
      if (!voxelCoordInRange(ix) || !voxelCoordInRange(iy) || !voxelCoordInRange(iz)) continue;  // +-1e6 voxels
      batch_key[b] = packVoxelKey(ix, iy, iz);
      __builtin_prefetch(&table_key[((batch_key[b] * 0x9E3779B97F4A7C15ull) >> 20) & mask]);
    }
    for (std::size_t b = 0; b < len; ++b) {
      const std::uint64_t key = batch_key[b];
      if (key == kEmpty) continue;
      const Eigen::Vector3f& p = points[i0 + b];
      if (key != last_key) {
        flushRun();
        std::size_t at = probe(key);
        if (table_key[at] == kEmpty) {
          if (2 * (keys.size() + 1) > capacity) {  // keep the load at most 1/2: rebuild twice as large
            capacity *= 2, mask = capacity - 1;
            table_key.assign(capacity, kEmpty);
            table_slot.assign(capacity, 0);
            for (std::size_t v = 0; v < keys.size(); ++v) {
              const std::size_t slot = probe(keys[v]);
              table_key[slot] = keys[v], table_slot[slot] = static_cast<std::uint32_t>(v);
            }
            at = probe(key);
          }
          table_key[at] = key;
          table_slot[at] = static_cast<std::uint32_t>(keys.size());
          keys.push_back(key);
          sums.emplace_back(Eigen::Vector3d::Zero());
          counts.push_back(0);
        }
        last_key = key, last_slot = table_slot[at];
        run_sum = sums[last_slot], run_count = counts[last_slot];
      }
      run_sum += p.cast<double>();
      ++run_count;
    }
  }
  flushRun();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(keys.size());
  for (std::size_t v = 0; v < keys.size(); ++v) order[v] = {keys[v], static_cast<std::uint32_t>(v)};
  radixSortByKey(order);  // = std::sort (keys are unique)
  out.reserve(order.size());
  for (const auto& [key, v] : order) out.push_back((sums[v] / static_cast<double>(counts[v])).cast<float>());
  return out;
}

}  // namespace cosmo
