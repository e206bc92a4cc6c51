#include "cosmo/common/kd_tree3.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>

namespace cosmo {

namespace {
/// Points per leaf (docs/benchmarks.md, k-d trees). The leaf size decides the offer order, and so which of two
/// points at the same distance is kept (the earlier offer): a change of it changes LOAM's results.
constexpr std::uint32_t kLeafSize = 12;

/// Blocks of four that hold the points [begin, end) of a leaf.
std::uint32_t blockCount(std::uint32_t begin, std::uint32_t end) { return (end - begin + 3) / 4; }
}  // namespace

void KnnResult::reset(int k, double max_dist) {
  k_ = std::clamp(k, 0, kMaxK);
  count_ = 0;
  bound_ = k_ > 0 ? static_cast<float>(max_dist * max_dist) : -1.0f;  // k = 0: nothing can enter
}

void KdTree3::build(std::vector<Eigen::Vector3d> points) { build(std::move(points), {}); }

void KdTree3::treeOrder(std::vector<std::uint32_t>& out) const {
  out.resize(sorted_.size());
  for (std::size_t i = 0; i < sorted_.size(); ++i) out[i] = sorted_[i].index;
}

void KdTree3::build(std::vector<Eigen::Vector3d> points, const std::vector<std::uint32_t>& order) {
  points_ = std::move(points);
  sorted_.clear();
  sorted_.reserve(points_.size());
  auto add = [this](std::uint32_t i) {
    const Eigen::Vector3d& p = points_[i];
    if (p.allFinite())
      sorted_.push_back({{static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())}, i});
  };
  bool ordered = !order.empty() && order.size() <= points_.size();
  if (ordered) {
    std::vector<std::uint8_t> seen(points_.size(), 0);
    for (std::uint32_t i : order) {
      if (i >= points_.size() || seen[i]) {
        ordered = false;
        break;
      }
      seen[i] = 1;
      add(i);
    }
    for (std::size_t i = 0; ordered && i < points_.size(); ++i)
      if (!seen[i] && points_[i].allFinite()) ordered = false;  // a finite point left out
    if (!ordered) sorted_.clear();
  }
  if (!ordered)
    for (std::size_t i = 0; i < points_.size(); ++i) add(static_cast<std::uint32_t>(i));
  nodes_.clear();
  blocks_.clear();
  depth_ = 0;
  if (sorted_.empty()) return;
  nodes_.reserve(4 * sorted_.size() / kLeafSize + 2);
  buildNode(0, static_cast<std::uint32_t>(sorted_.size()), 0);
  makeBlocks();
}

void KdTree3::makeBlocks() {
  std::size_t count = 0;
  for (const Node& node : nodes_)
    if (node.axis < 0) count += blockCount(node.begin, node.end);
  blocks_.resize(count);
  // NaN padding: its distance is NaN, which no bound test passes (an infinite point would pass an infinite bound).
  const float pad = std::numeric_limits<float>::quiet_NaN();
  std::uint32_t b = 0;
  for (Node& node : nodes_) {
    if (node.axis >= 0) continue;
    node.right = b;
    for (std::uint32_t i = node.begin; i < node.end; i += 4, ++b) {
      Block& block = blocks_[b];
      for (std::uint32_t j = 0; j < 4; ++j) {
        const bool real = i + j < node.end;
        const SortedPoint* p = real ? &sorted_[i + j] : nullptr;
        block.x[j] = real ? p->c[0] : pad;
        block.y[j] = real ? p->c[1] : pad;
        block.z[j] = real ? p->c[2] : pad;
        block.index[j] = real ? p->index : 0;
      }
    }
  }
}

std::uint32_t KdTree3::buildNode(std::uint32_t begin, std::uint32_t end, int depth) {
  depth_ = std::max(depth_, depth);
  const auto id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin <= kLeafSize) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  // The widest extent of this node's points. With SSE2 a SortedPoint is one 16-byte register (x y z and the
  // index, whose lane is ignored): two instructions per point. min / max are exact, and the operand order is
  // std::min / std::max's, so the box is bit for bit the per-coordinate one.
  float lo_c[4], hi_c[4];
#if defined(__SSE2__)
  static_assert(sizeof(SortedPoint) == 4 * sizeof(float), "a SortedPoint is loaded as one SSE register");
  __m128 lo = _mm_loadu_ps(sorted_[begin].c), hi = lo;
  for (std::uint32_t i = begin + 1; i < end; ++i) {
    const __m128 c = _mm_loadu_ps(sorted_[i].c);
    lo = _mm_min_ps(c, lo);  // (c < lo) ? c : lo, as std::min(lo, c)
    hi = _mm_max_ps(c, hi);  // (c > hi) ? c : hi, as std::max(hi, c)
  }
  _mm_storeu_ps(lo_c, lo);
  _mm_storeu_ps(hi_c, hi);
#else
  for (int a = 0; a < 3; ++a) lo_c[a] = hi_c[a] = sorted_[begin].c[a];
  for (std::uint32_t i = begin + 1; i < end; ++i)
    for (int a = 0; a < 3; ++a) {
      lo_c[a] = std::min(lo_c[a], sorted_[i].c[a]);
      hi_c[a] = std::max(hi_c[a], sorted_[i].c[a]);
    }
#endif
  const float extent[3] = {hi_c[0] - lo_c[0], hi_c[1] - lo_c[1], hi_c[2] - lo_c[2]};
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (extent[a] > extent[axis]) axis = a;
  // Split at the middle of the extent (one partition pass; on points clustered on surfaces it also gave
  // better-pruning cells than the median), at the median when that leaves one side empty (rounding, equal
  // coordinates), so that every split makes progress.
  float split = lo_c[axis] + 0.5f * extent[axis];
  auto first = sorted_.begin() + begin, last = sorted_.begin() + end;
  auto mid_it = std::partition(first, last, [axis, split](const SortedPoint& p) { return p.c[axis] < split; });
  if (mid_it == first || mid_it == last) {
    mid_it = first + (end - begin) / 2;
    std::nth_element(first, mid_it, last,
                     [axis](const SortedPoint& a, const SortedPoint& b) { return a.c[axis] < b.c[axis]; });
    split = mid_it->c[axis];
  }
  const auto mid = static_cast<std::uint32_t>(mid_it - sorted_.begin());
  buildNode(begin, mid, depth + 1);  // left: coordinates <= split (< split unless the median fallback was used)
  const std::uint32_t right = buildNode(mid, end, depth + 1);  // right: coordinates >= split
  nodes_[id].axis = axis;
  nodes_[id].split = split;
  nodes_[id].right = right;
  return id;
}

namespace {
/// The leaf scan, a function local to this file so that search() inlines it (a member function of a shared
/// library is called through the PLT: it may be interposed). The squared distance is ((dx^2 + dy^2) + dz^2) in
/// float, as before the blocks; the points that pass the bound at the block's start are offered in leaf order,
/// and offer() tests each against the bound as it is then: the same result as testing point by point.
template <typename Block>
inline void scanBlocks(const Block* block, std::uint32_t count, const float q[3], KnnResult& result) {
#if defined(__SSE2__)
  const __m128 qx = _mm_set1_ps(q[0]), qy = _mm_set1_ps(q[1]), qz = _mm_set1_ps(q[2]);
  for (const Block* end = block + count; block != end; ++block) {
    const __m128 dx = _mm_sub_ps(qx, _mm_load_ps(block->x));
    const __m128 dy = _mm_sub_ps(qy, _mm_load_ps(block->y));
    const __m128 dz = _mm_sub_ps(qz, _mm_load_ps(block->z));
    const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    int pass = _mm_movemask_ps(_mm_cmple_ps(d2, _mm_set1_ps(result.bound())));
    if (pass == 0) continue;
    alignas(16) float d[4];
    _mm_store_ps(d, d2);
    do {
      const int j = __builtin_ctz(static_cast<unsigned>(pass));
      pass &= pass - 1;
      result.offer(d[j], block->index[j]);
    } while (pass != 0);
  }
#else
  for (const Block* end = block + count; block != end; ++block)
    for (int j = 0; j < 4; ++j) {
      const float dx = q[0] - block->x[j], dy = q[1] - block->y[j], dz = q[2] - block->z[j];
      const float d2 = dx * dx + dy * dy + dz * dz;
      if (d2 <= result.bound()) result.offer(d2, block->index[j]);
    }
#endif
}
}  // namespace

void KdTree3::scanLeaf(const Node& node, const float q[3], KnnResult& result) const {
  scanBlocks(blocks_.data() + node.right, blockCount(node.begin, node.end), q, result);
}

void KdTree3::searchNode(std::uint32_t n, const float q[3], float offset[3], float min_d2, KnnResult& result) const {
  const Node& node = nodes_[n];
  if (node.axis < 0) {
    scanLeaf(node, q, result);
    return;
  }
  // The far child's cell is at least |diff| away along the split axis: its squared distance lower bound is
  // min_d2 with this axis' term replaced (Arya & Mount's incremental distance).
  const int a = node.axis;
  const float diff = q[a] - node.split;
  const std::uint32_t near = diff < 0.0f ? n + 1 : node.right;
  const std::uint32_t far = diff < 0.0f ? node.right : n + 1;
  searchNode(near, q, offset, min_d2, result);
  const float old_offset = offset[a];
  const float far_d2 = min_d2 - old_offset * old_offset + diff * diff;
  if (far_d2 <= result.bound()) {
    offset[a] = diff;
    searchNode(far, q, offset, far_d2, result);
    offset[a] = old_offset;
  }
}

void KdTree3::search(const Eigen::Vector3d& query, KnnResult& result) const {
  if (nodes_.empty()) return;
  const float q[3] = {static_cast<float>(query.x()), static_cast<float>(query.y()), static_cast<float>(query.z())};
  float offset[3] = {0.0f, 0.0f, 0.0f};
  if (depth_ >= kMaxStack) {  // a degenerate, very deep tree: the recursive search has no depth limit
    searchNode(0, q, offset, 0.0f, result);
    return;
  }
  // The recursive search without calls: the far children wait on a stack with their cell offsets and are
  // visited in the same order (nearest subtree first, then the pending far cells, latest first), each only
  // when its lower bound is still within the result's bound when its turn comes.
  struct Pending {
    std::uint32_t node;
    float d2;
    float offset[3];
  };
  Pending stack[kMaxStack];
  int top = 0;
  std::uint32_t n = 0;
  float min_d2 = 0.0f;
  for (;;) {
    const Node& node = nodes_[n];
    if (node.axis >= 0) {
      const int a = node.axis;
      const float diff = q[a] - node.split;
      const float far_d2 = min_d2 - offset[a] * offset[a] + diff * diff;
      const std::uint32_t far = diff < 0.0f ? node.right : n + 1;
      n = diff < 0.0f ? n + 1 : node.right;
      Pending& p = stack[top];  // written always, kept only when within the bound (no branch)
      p.node = far;
      p.d2 = far_d2;
      p.offset[0] = offset[0], p.offset[1] = offset[1], p.offset[2] = offset[2];
      p.offset[a] = diff;
      top += far_d2 <= result.bound() ? 1 : 0;
      continue;
    }
    scanBlocks(blocks_.data() + node.right, blockCount(node.begin, node.end), q, result);
    for (;;) {
      if (top == 0) return;
      const Pending& p = stack[--top];
      if (p.d2 <= result.bound()) {
        n = p.node;
        min_d2 = p.d2;
        offset[0] = p.offset[0], offset[1] = p.offset[1], offset[2] = p.offset[2];
        break;
      }
    }
  }
}

void KdTree3::knn(const Eigen::Vector3d& query, int k, double max_dist, std::vector<std::size_t>& indices) const {
  indices.clear();
  KnnResult result;
  result.reset(k, max_dist);
  search(query, result);
  for (int i = 0; i < result.size(); ++i) indices.push_back(result.index(i));
}

}  // namespace cosmo
