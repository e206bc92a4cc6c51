#pragma once
// Integer voxel (grid cell) coordinates and their 64-bit key, shared by every voxel grid and hash grid of the
// project. Each axis is offset by 2^20 and takes 21 bits, x highest: keys of cells within +-2^20 cells of the
// origin are unique and sort by (x, y, z).
#include <cmath>
#include <cstdint>

namespace cosmo {

constexpr std::int64_t kVoxelKeyOffset = std::int64_t{1} << 20;  ///< offset coordinates lie in [0, 2^21)
constexpr std::uint64_t kVoxelKeyAxisMask = (std::uint64_t{1} << 21) - 1;

/// Offset cell coordinate of `v` on a grid of cell size 1 / inv_cell (floor; the same value as std::floor, which
/// without SSE4.1 is a libm call: truncation corrected by one below zero).
inline std::int64_t voxelCoord(double v, double inv_cell) {
  const double t = v * inv_cell;
  const auto i = static_cast<std::int64_t>(t);
  return i - (static_cast<double>(i) > t ? 1 : 0) + kVoxelKeyOffset;
}

/// True when an offset coordinate has `margin` cells of room on both sides inside [0, 2^21).
inline bool voxelCoordInRange(std::int64_t c, std::int64_t margin = 0) {
  return c >= margin && c < 2 * kVoxelKeyOffset - margin;
}

/// The key of offset coordinates (each in [0, 2^21); wider values are wrapped to 21 bits).
inline std::uint64_t packVoxelKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  return ((static_cast<std::uint64_t>(x) & kVoxelKeyAxisMask) << 42) |
         ((static_cast<std::uint64_t>(y) & kVoxelKeyAxisMask) << 21) |
         (static_cast<std::uint64_t>(z) & kVoxelKeyAxisMask);
}

}  // namespace cosmo
