#include "cosmo/registration/neighbour_pairs.hpp"

#include <algorithm>
#include <cmath>

#include "cosmo/common/voxel_key.hpp"
#include "cosmo/common/radix_sort.hpp"

namespace cosmo::registration {

namespace {

/// out[k] = ((x[k] - ax)^2 + (y[k] - ay)^2) + (z[k] - az)^2, k < len (Eigen packets; flattened so that they
/// are inlined).
__attribute__((flatten)) void squaredDistances(const float* x, const float* y, const float* z, Eigen::Index len,
                                               float ax, float ay, float az, float* out) {
  using Run = Eigen::Map<const Eigen::ArrayXf>;
  Eigen::Map<Eigen::ArrayXf> d2(out, len);
  d2 = (Run(x, len) - ax).square() + (Run(y, len) - ay).square() + (Run(z, len) - az).square();
}

NeighbourPairs findPairs(const std::vector<Eigen::Vector3f>& points, float radius, std::vector<std::uint32_t>* order);

}  // namespace

NeighbourPairs findNeighbourPairs(const std::vector<Eigen::Vector3f>& points, float radius) {
  return findPairs(points, radius, nullptr);
}

NeighbourPairs findNeighbourPairs(const std::vector<Eigen::Vector3f>& points, float radius,
                                  std::vector<std::uint32_t>& order) {
  return findPairs(points, radius, &order);
}

namespace {

NeighbourPairs findPairs(const std::vector<Eigen::Vector3f>& points, float radius, std::vector<std::uint32_t>* order) {
  NeighbourPairs out;
  const std::size_t n = points.size();
  if (order != nullptr) order->clear();
  if (n < 2 || !(radius > 0.f)) return out;
  const float r2 = radius * radius;
  const double inv = 1.0 / static_cast<double>(radius);
  // Points sorted by cell (then by index): each cell is a contiguous run of a structure-of-arrays copy.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = points[i];
    if (!p.allFinite()) continue;
    const std::int64_t cx = voxelCoord(p.x(), inv), cy = voxelCoord(p.y(), inv), cz = voxelCoord(p.z(), inv);
    // one cell of room on each side: the forward neighbours' keys below must not wrap
    if (!voxelCoordInRange(cx, 1) || !voxelCoordInRange(cy, 1) || !voxelCoordInRange(cz, 1)) continue;
    keyed.emplace_back(packVoxelKey(cx, cy, cz), static_cast<std::uint32_t>(i));
  }
  radixSortByKey(keyed);  // = std::sort: the input is in index order
  const std::size_t m = keyed.size();
  std::vector<float> xs(m), ys(m), zs(m);
  std::vector<std::uint32_t> ids(m);
  std::vector<std::uint64_t> cell_key;
  std::vector<std::uint32_t> cell_begin;
  for (std::size_t s = 0; s < m; ++s) {
    const Eigen::Vector3f& p = points[keyed[s].second];
    xs[s] = p.x(), ys[s] = p.y(), zs[s] = p.z();
    ids[s] = keyed[s].second;
    if (s == 0 || keyed[s].first != keyed[s - 1].first) {
      cell_key.push_back(keyed[s].first);
      cell_begin.push_back(static_cast<std::uint32_t>(s));
    }
  }
  cell_begin.push_back(static_cast<std::uint32_t>(m));
  if (order != nullptr) {  // pairs labelled by position instead of input index
    *order = ids;
    for (std::size_t s = 0; s < m; ++s) ids[s] = static_cast<std::uint32_t>(s);
  }
  const std::size_t cells = cell_key.size();
  out.resize(n * 32);
  std::vector<float> d2_buffer;
  // The 13 forward neighbour offsets: (dx, dy, dz) lexicographically after (0, 0, 0).
  std::int64_t forward[13];
  int nf = 0;
  for (int dx = 0; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        if (dx > 0 || (dx == 0 && (dy > 0 || (dy == 0 && dz > 0))))
          forward[nf++] = (static_cast<std::int64_t>(dx) << 42) + (static_cast<std::int64_t>(dy) << 21) + dz;
  // Squared distances of one point to a run of points (vectorised), then the close ones appended without a
  // branch (each candidate is written, the end advances only for the close ones).
  std::size_t used = 0;
  auto emitPairs = [&](std::uint32_t a0, std::uint32_t a1, std::uint32_t b0, std::uint32_t b1, bool same) {
    for (std::uint32_t a = a0; a < a1; ++a) {
      const std::uint32_t first = same ? a + 1 : b0;
      if (first >= b1) continue;
      const std::size_t len = b1 - first;
      if (d2_buffer.size() < len) d2_buffer.resize(len);
      squaredDistances(xs.data() + first, ys.data() + first, zs.data() + first, static_cast<Eigen::Index>(len), xs[a],
                       ys[a], zs[a], d2_buffer.data());
      if (out.size() < used + len) out.resize(std::max(2 * out.size(), used + len));
      NeighbourPair* dst = out.data() + used;
      const std::uint32_t ia = ids[a];
      std::size_t k_out = 0;
      for (std::size_t k = 0; k < len; ++k) {
        const float d2 = d2_buffer[k];
        dst[k_out] = {ia, ids[first + k], d2};
        k_out += d2 < r2 ? 1 : 0;
      }
      used += k_out;
    }
  };
  // Each forward neighbour's key grows with the cell's key, so its cell is found by a cursor per offset that
  // only moves forward over the sorted keys (a merge walk instead of a binary search per cell and offset).
  std::size_t cursor[13] = {};
  for (std::size_t c = 0; c < cells; ++c) {
    emitPairs(cell_begin[c], cell_begin[c + 1], cell_begin[c], cell_begin[c + 1], true);
    for (int f = 0; f < nf; ++f) {
      // Packed keys add per axis without carries (every cell is at least one away from the packing bounds).
      const std::uint64_t key = static_cast<std::uint64_t>(static_cast<std::int64_t>(cell_key[c]) + forward[f]);
      std::size_t& d = cursor[f];
      while (d < cells && cell_key[d] < key) ++d;
      if (d == cells || cell_key[d] != key) continue;
      emitPairs(cell_begin[c], cell_begin[c + 1], cell_begin[d], cell_begin[d + 1], false);
    }
  }
  out.resize(used);
  return out;
}

}  // namespace

}  // namespace cosmo::registration
