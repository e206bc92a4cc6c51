#include "cosmo/odometry/feature_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>

#include "cosmo/common/voxel_grid.hpp"

namespace cosmo::odometry {

std::vector<float> computeCurvature(const ScanLine& line, const LoamParams& params) {
  const int n = static_cast<int>(line.points.size());
  const int N = std::max(1, params.neighbor_points);
  std::vector<float> curv(n, -1.0f);
  // Distance (in points) to the previous break: the curvature needs N continuous neighbours on each side.
  int since_break = 0;
  std::vector<int> left(n), right(n);
  for (int i = 0; i < n; ++i) {
    if (i == 0 || line.break_before[i]) since_break = 0;
    left[i] = since_break++;
  }
  int until_break = 0;
  for (int i = n - 1; i >= 0; --i) {
    right[i] = until_break++;
    if (line.break_before[i]) until_break = 0;
  }
  for (int i = N; i + N < n; ++i) {
    if (left[i] < N || right[i] < N) continue;
    Eigen::Vector3f d = -2.0f * static_cast<float>(N) * line.points[i];
    for (int j = 1; j <= N; ++j) d += line.points[i - j] + line.points[i + j];
    curv[i] = d.squaredNorm();
  }
  return curv;
}

std::vector<std::uint8_t> computeValidPoints(const ScanLine& line, const LoamParams& params) {
  const int n = static_cast<int>(line.points.size());
  const int N = std::max(1, params.neighbor_points);
  std::vector<std::uint8_t> valid(n, 1);
  // Rule 1: the first / last N points of a line (and around gaps) have no full neighbourhood.
  for (int i = 0; i < n; ++i) {
    const bool start = (i == 0 || line.break_before[i]);
    if (start) {
      for (int k = 0; k < N && i + k < n; ++k) valid[i + k] = 0;
      for (int k = 1; k <= N && i - k >= 0; ++k) valid[i - k] = 0;
    }
  }
  for (int k = 0; k < N && n - 1 - k >= 0; ++k) valid[n - 1 - k] = 0;
  if (n < 3) return valid;
  std::vector<float> range(n);
  for (int i = 0; i < n; ++i) range[i] = line.points[i].norm();
  for (int i = 1; i + 1 < n; ++i) {
    // Rule 2: occlusion boundary. The far side of a range jump between neighbours is (possibly) occluded:
    // invalidate it and its N neighbours away from the jump; the near side is a real corner and stays.
    if (!line.break_before[i + 1]) {
      const float jump = range[i + 1] - range[i];
      if (jump > params.occlusion_thresh) {
        for (int k = 1; k <= N + 1 && i + k < n; ++k) valid[i + k] = 0;
      } else if (-jump > params.occlusion_thresh) {
        for (int k = 0; k <= N && i - k >= 0; ++k) valid[i - k] = 0;
      }
    }
    // Rule 3: surface nearly parallel to the beam: the range changes by a large fraction of the range to both
    // neighbours.
    const float thr = static_cast<float>(params.parallel_thresh) * range[i];
    if (std::abs(range[i - 1] - range[i]) > thr && std::abs(range[i + 1] - range[i]) > thr) valid[i] = 0;
  }
  return valid;
}

namespace {
/// Sorts keys (curvature bits << 32 | point index), given in increasing index order, ascending: a stable LSD
/// radix sort on the 32 curvature bits, 8 at a time (passes where all keys share the byte are skipped). The
/// same order as std::sort of the 64-bit keys (ties by index), without its mispredicted comparisons (~3x
/// faster on the ~170 keys of a sector).
void sortCurvatureKeys(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& tmp) {
  const std::size_t n = keys.size();
  if (n < 2) return;
  tmp.resize(n);
  std::uint64_t* src = keys.data();
  std::uint64_t* dst = tmp.data();
  for (int shift = 32; shift < 64; shift += 8) {
    std::uint32_t count[256] = {};
    for (std::size_t i = 0; i < n; ++i) ++count[(src[i] >> shift) & 0xFFu];
    if (count[(src[0] >> shift) & 0xFFu] == n) continue;  // one bucket: already in order for this byte
    std::uint32_t sum = 0;
    for (std::uint32_t& c : count) {
      const std::uint32_t here = c;
      c = sum;
      sum += here;
    }
    for (std::size_t i = 0; i < n; ++i) dst[count[(src[i] >> shift) & 0xFFu]++] = src[i];
    std::swap(src, dst);
  }
  if (src != keys.data()) std::copy(src, src + n, keys.data());
}
}  // namespace

LoamFeatures extractFeatures(const ScanLines& lines, const LoamParams& params) {
  LoamFeatures out;
  const int N = std::max(1, params.neighbor_points);
  const int sectors = std::max(1, params.number_sectors);
  std::vector<std::uint64_t> order, scratch;
  for (const ScanLine& line : lines.lines) {
    const int n = static_cast<int>(line.points.size());
    if (n < 2 * N + 1) continue;
    const bool has_time = line.time.size() == line.points.size();
    std::vector<std::uint8_t> valid = computeValidPoints(line, params);
    const std::vector<float> curv = computeCurvature(line, params);
    const int per_sector = n / sectors;
    auto pick = [&](int i, std::vector<Eigen::Vector3d>& pts, std::vector<float>& times) {
      pts.push_back(line.points[i].cast<double>());
      if (has_time) times.push_back(line.time[i]);
      for (int k = -N; k <= N; ++k)
        if (i + k >= 0 && i + k < n) valid[i + k] = 0;
    };
    for (int s = 0; s < sectors; ++s) {
      const int begin = s * per_sector;
      const int end = (s == sectors - 1) ? n : begin + per_sector;
      // Points by (curvature, index): one 64-bit key each (a non-negative float's bits order like the float),
      // sorted without indirection. Only points that can be picked enter: valid now (picks only invalidate)
      // and an edge or planar candidate, so the walks below pick exactly as over all points.
      order.clear();
      for (int i = begin; i < end; ++i) {
        if (!(curv[i] >= 0.0f) || !valid[i]) continue;
        if (!(curv[i] > params.edge_feat_threshold) && !(curv[i] < params.planar_feat_threshold)) continue;
        std::uint32_t bits;
        std::memcpy(&bits, &curv[i], sizeof bits);
        order.push_back((static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint32_t>(i));
      }
      sortCurvatureKeys(order, scratch);
      auto index = [](std::uint64_t key) { return static_cast<int>(key & 0xFFFFFFFFu); };
      // Edges: largest curvature first.
      int edges = 0;
      for (auto it = order.rbegin(); it != order.rend() && edges < params.max_edge_feats_per_sector; ++it) {
        if (curv[index(*it)] <= params.edge_feat_threshold) break;
        if (!valid[index(*it)]) continue;
        pick(index(*it), out.edge_points, out.edge_time);
        ++edges;
      }
      // Planar: smallest curvature first.
      int planes = 0;
      for (auto it = order.begin(); it != order.end() && planes < params.max_planar_feats_per_sector; ++it) {
        if (curv[index(*it)] >= params.planar_feat_threshold) break;
        if (!valid[index(*it)]) continue;
        pick(index(*it), out.planar_points, out.planar_time);
        ++planes;
      }
    }
  }
  return out;
}

void thinPlanarFeatures(LoamFeatures& f, double voxel_size) {
  if (!(voxel_size > 0.0)) return;
  const auto keep = voxelFilterIndices(f.planar_points, voxel_size);
  const bool timed = f.planar_time.size() == f.planar_points.size();
  for (std::size_t j = 0; j < keep.size(); ++j) {  // keep is ascending: in-place compaction
    f.planar_points[j] = f.planar_points[keep[j]];
    if (timed) f.planar_time[j] = f.planar_time[keep[j]];
  }
  f.planar_points.resize(keep.size());
  if (timed) f.planar_time.resize(keep.size());
}

}  // namespace cosmo::odometry
