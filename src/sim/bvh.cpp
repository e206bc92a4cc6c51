#include "cosmo/sim/bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace cosmo::sim {

Bvh::Bvh(std::vector<Primitive> primitives, int max_leaf_size) {
  const auto n = static_cast<std::uint32_t>(primitives.size());
  if (n == 0) return;
  std::vector<std::uint32_t> order(n);
  std::vector<Aabb> boxes(n);
  std::vector<Eigen::Vector3d> centers(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    order[i] = i;
    boxes[i] = primitives[i].bounds();
    centers[i] = boxes[i].center();
  }
  nodes_.reserve(2 * n);
  build(order, boxes, centers, 0, n, std::max(1, max_leaf_size));
  prims_.reserve(n);
  for (auto i : order) prims_.push_back(primitives[i]);
}

// Binned surface-area heuristic; falls back to a median split when no bin split helps.
std::uint32_t Bvh::build(std::vector<std::uint32_t>& order, std::vector<Aabb>& boxes,
                         std::vector<Eigen::Vector3d>& centers, std::uint32_t begin, std::uint32_t end, int max_leaf) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Aabb box, cbox;
  for (auto i = begin; i < end; ++i) {
    box.extend(boxes[order[i]]);
    cbox.extend(centers[order[i]]);
  }
  for (int a = 0; a < 3; ++a) {
    nodes_[index].lo[a] = std::nextafter(static_cast<float>(box.lo[a]), -std::numeric_limits<float>::infinity());
    nodes_[index].hi[a] = std::nextafter(static_cast<float>(box.hi[a]), std::numeric_limits<float>::infinity());
  }
  const std::uint32_t count = end - begin;
  auto makeLeaf = [&]() {
    nodes_[index].first = begin;
    nodes_[index].count = static_cast<std::uint16_t>(count);
    return index;
  };
  if (count <= 2) return makeLeaf();
  constexpr int kBins = 16;
  int best_axis = -1;
  double best_cost = std::numeric_limits<double>::infinity(), best_split = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = cbox.lo[axis], ext = cbox.hi[axis] - cbox.lo[axis];
    if (ext < 1e-9) continue;
    std::array<Aabb, kBins> bin_box;
    std::array<std::uint32_t, kBins> bin_n{};
    for (auto i = begin; i < end; ++i) {
      const int b = std::min(kBins - 1, static_cast<int>(kBins * (centers[order[i]][axis] - lo) / ext));
      bin_box[b].extend(boxes[order[i]]);
      ++bin_n[b];
    }
    std::array<double, kBins> right_area{};
    std::array<std::uint32_t, kBins> right_n{};
    Aabb acc;
    std::uint32_t acc_n = 0;
    for (int b = kBins - 1; b > 0; --b) {
      acc.extend(bin_box[b]);
      acc_n += bin_n[b];
      right_area[b] = acc_n ? acc.area() : 0.0;
      right_n[b] = acc_n;
    }
    Aabb left;
    std::uint32_t left_n = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      left.extend(bin_box[b]);
      left_n += bin_n[b];
      if (left_n == 0 || right_n[b + 1] == 0) continue;
      const double cost = left_n * left.area() + right_n[b + 1] * right_area[b + 1];
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_split = lo + ext * (b + 1) / kBins;
      }
    }
  }
  const double leaf_cost = count * box.area();
  std::uint32_t mid;
  int axis = best_axis;
  if (best_axis >= 0 && (best_cost + box.area() < leaf_cost || count > static_cast<std::uint32_t>(max_leaf))) {
    mid = static_cast<std::uint32_t>(std::partition(order.begin() + begin, order.begin() + end,
                                                    [&](std::uint32_t k) { return centers[k][axis] < best_split; }) -
                                     order.begin());
  } else if (count <= static_cast<std::uint32_t>(max_leaf) || best_axis < 0) {
    if (count <= 64 || best_axis < 0) return makeLeaf();
    mid = begin + count / 2;
  } else {
    mid = begin + count / 2;
  }
  if (mid == begin || mid == end) {
    (cbox.hi - cbox.lo).maxCoeff(&axis);
    mid = begin + count / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) { return centers[a][axis] < centers[b][axis]; });
  }
  build(order, boxes, centers, begin, mid, max_leaf);
  const auto right = build(order, boxes, centers, mid, end, max_leaf);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  nodes_[index].axis = static_cast<std::uint8_t>(std::max(axis, 0));
  return index;
}

Aabb Bvh::bounds() const {
  Aabb b;
  if (!nodes_.empty())
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = nodes_[0].lo[a];
      b.hi[a] = nodes_[0].hi[a];
    }
  return b;
}

namespace {
struct FloatRay {
  float o[3], inv[3];
};
// Branchless slab test; true when the box is met within [0, t_max].
inline bool slab(const float* lo, const float* hi, const FloatRay& r, float t_max, float& t_enter) {
  float t0 = 0.0f, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const float ta = (lo[a] - r.o[a]) * r.inv[a];
    const float tb = (hi[a] - r.o[a]) * r.inv[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  t_enter = t0;
  return t0 <= t1;
}
}  // namespace

bool Bvh::intersect(const Ray& ray, double t_min, Hit& hit) const {
  if (nodes_.empty()) return false;
  FloatRay fr;
  for (int a = 0; a < 3; ++a) {
    fr.o[a] = static_cast<float>(ray.o[a]);
    // Clamp infinities so that 0 * inf never produces NaN in the slab test.
    const double inv = ray.inv_d[a];
    fr.inv[a] = static_cast<float>(std::isfinite(inv) ? std::clamp(inv, -1e30, 1e30) : (inv > 0 ? 1e30 : -1e30));
  }
  // Float boxes are rounded outwards; pad the range limit by float precision.
  auto limit = [&]() { return static_cast<float>(hit.t) * 1.0001f + 1e-3f; };
  float t_root;
  if (!slab(nodes_[0].lo, nodes_[0].hi, fr, limit(), t_root)) return false;
  struct Entry {
    std::uint32_t node;
    float t;
  };
  Entry stack[64];
  int top = 0;
  bool found = false;
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        found |= prims_[i].intersect(ray, t_min, hit);
    } else {
      const std::uint32_t left = current + 1, right = node.first;
      float tl, tr;
      const float tm = limit();
      const bool hl = slab(nodes_[left].lo, nodes_[left].hi, fr, tm, tl);
      const bool hr = slab(nodes_[right].lo, nodes_[right].hi, fr, tm, tr);
      if (hl && hr) {
        if (tl <= tr) {
          stack[top++] = {right, tr};
          current = left;
        } else {
          stack[top++] = {left, tl};
          current = right;
        }
        continue;
      }
      if (hl) {
        current = left;
        continue;
      }
      if (hr) {
        current = right;
        continue;
      }
    }
    // Pop the next node that can still hold a closer hit.
    for (;;) {
      if (top == 0) return found;
      const Entry e = stack[--top];
      if (e.t <= limit()) {
        current = e.node;
        break;
      }
    }
  }
}

}  // namespace cosmo::sim
