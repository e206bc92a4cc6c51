#pragma once
// Kd-tree over float rows (3-D points, 33-D feature vectors), single index, deterministic. Own implementation of
// the sliding-midpoint tree that nanoflann 1.4 builds (split the widest bounding-box side at its middle, clamped
// to the points' range; leaves of at most 10 rows, 64 for features) and of its best-bin-first search with
// incremental distances to the cells and (1+eps) pruning: the same tree, the same visiting order, the same
// answers bit for bit (test_kdtree checks this against nanoflann). Differences, for speed only: the rows are
// copied in leaf order (a leaf is one contiguous block, feature rows padded to 16-byte aligned 36-float rows),
// the nodes live in one array in depth-first order (first child = next node), and the search loops are written
// for a single nearest neighbour. The data is copied: it need not outlive the tree. Measured against nanoflann
// itself on 33-D FPFH-like rows (bench_kd_trees: 5k rows, 5k (1+10)-approximate queries): build 0.9 ms against
// 9.9 ms, queries 2.4 us against 6.3 us, identical answers.
// The k-d trees of cosmo: this one (nearest row, rows within a radius: registration's feature matching, ICP,
// graph pruning) and KdTree3 (kd_tree3.hpp: the k nearest 3-D points within a bound, LOAM's local map, where this
// tree, having no k-nearest query, takes 401 ms against 8.0 ms in bench_kd_trees). ScanContext's ring-key index uses
// nanoflann itself: its dimension is a run-time parameter (the ring count) and a query costs 0.23 ms in all.
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace cosmo {

template <int Dim>
class KdTree {
 public:
  /// `data` holds `count` rows of `Dim` floats (e.g. std::vector<Eigen::Vector3f>::data()->data()).
  KdTree(const float* data, std::size_t count) : count_(count) { build(data); }
  std::size_t size() const { return count_; }

  /// Nearest neighbour: (index, squared distance); (-1, inf) for an empty tree. With eps > 0 the search is
  /// (1+eps)-approximate (still deterministic).
  std::pair<int, float> nearest(const float* query, float eps = 0.f) const {
    if (count_ == 0) return {-1, std::numeric_limits<float>::infinity()};
    Nearest s{std::numeric_limits<float>::max(), kNone};
    search(s, query, 1.f + eps);
    return {s.row == kNone ? 0 : static_cast<int>(ids_[s.row]), s.d2};  // row 0 when nothing is below max()
  }

  /// Nearest neighbour within squared distance `max_d2` (the bound prunes the search: far queries are cheap);
  /// (-1, inf) when there is none. Same answer as nearest() when that one is within the bound.
  std::pair<int, float> nearestWithin(const float* query, float max_d2) const {
    if (count_ == 0) return {-1, std::numeric_limits<float>::infinity()};
    Nearest s{std::nextafter(max_d2, std::numeric_limits<float>::infinity()), kNone};  // only closer points
    search(s, query, 1.f);
    if (s.row == kNone) return {-1, std::numeric_limits<float>::infinity()};
    return {static_cast<int>(ids_[s.row]), s.d2};
  }

  /// Whether some row lies within squared distance `max_d2` (inclusive) of the query: the search stops at the
  /// first one found, so it is cheaper than nearestWithin(); the same verdict.
  bool anyWithin(const float* query, float max_d2) const {
    if (count_ == 0) return false;
    FirstHit s{std::nextafter(max_d2, std::numeric_limits<float>::infinity())};
    search(s, query, 1.f);
    return s.found;
  }

  /// All rows within `radius` as (index, squared distance), in the tree's order (deterministic); their count.
  std::size_t radius(const float* query, float radius, std::vector<std::pair<std::uint32_t, float>>& out) const {
    out.clear();
    if (count_ == 0) return 0;
    Within s{radius * radius, this, &out};
    search(s, query, 1.f);
    return out.size();
  }

 private:
  static constexpr bool kWide = Dim > 4;
  static constexpr std::size_t kStride = kWide ? (Dim + 3) / 4 * 4 : Dim;  ///< floats per stored row
  static constexpr std::size_t kLeafMax = kWide ? 64 : 10;
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  using Rows = std::vector<float, Eigen::aligned_allocator<float>>;
  struct Interval {
    float low, high;
  };
  using Box = std::array<Interval, Dim>;
  /// Inner node: cut dimension `dim` >= 0, the left points' highest and the right points' lowest value on it,
  /// first child at the next index, second child at `second`. Leaf: dim = -1, rows [begin, end).
  struct Node {
    std::int32_t dim;
    std::uint32_t begin, end, second;
    float low, high;
  };

  /// Squared distance of the query to stored row r, computed as nanoflann's metrics do: a whole-row Eigen
  /// expression for the features, a plain ((0 + dx^2) + dy^2) + dz^2 sum for points.
  float rowDistance(const float* q, std::size_t r) const {
    const float* row = rows_.data() + r * kStride;
    if constexpr (kWide) {
      using Row = Eigen::Map<const Eigen::Matrix<float, Dim, 1>>;
      return (Row(q) - Row(row)).squaredNorm();
    } else {
      float d2 = 0.f;
      for (int k = 0; k < Dim; ++k) {
        const float diff = q[k] - row[k];
        d2 += diff * diff;
      }
      return d2;
    }
  }

  struct Nearest {
    float d2;
    std::uint32_t row;
    float bound() const { return d2; }
    bool add(float d, std::uint32_t r) {
      if (d < d2) d2 = d, row = r;
      return true;
    }
  };
  struct FirstHit {
    float d2;
    bool found = false;
    float bound() const { return d2; }
    bool add(float, std::uint32_t) {
      found = true;
      return false;
    }
  };
  struct Within {
    float d2;
    const KdTree* tree;
    std::vector<std::pair<std::uint32_t, float>>* out;
    float bound() const { return d2; }
    bool add(float d, std::uint32_t r) {
      out->emplace_back(tree->ids_[r], d);
      return true;
    }
  };

  template <class Result>
  void search(Result& result, const float* q, float eps_factor) const {
    std::array<float, Dim> cell{};  // per dimension: squared distance of the query to the current cell
    float d2 = 0.f;
    for (int k = 0; k < Dim; ++k) {
      if (q[k] < root_[k].low) {
        cell[k] = (q[k] - root_[k].low) * (q[k] - root_[k].low);
        d2 += cell[k];
      }
      if (q[k] > root_[k].high) {
        cell[k] = (q[k] - root_[k].high) * (q[k] - root_[k].high);
        d2 += cell[k];
      }
    }
    searchNode(result, q, 0, d2, cell, eps_factor);
  }

  /// Returns false when the result wants no more points.
  template <class Result>
  bool searchNode(Result& result, const float* q, std::uint32_t at, float cell_d2, std::array<float, Dim>& cell,
                  float eps_factor) const {
    const Node& node = nodes_[at];
    if (node.dim < 0) {
      const float bound = result.bound();  // read once per leaf, as nanoflann does
      for (std::uint32_t r = node.begin; r < node.end; ++r) {
        const float d = rowDistance(q, r);
        if (d < bound && !result.add(d, r)) return false;
      }
      return true;
    }
    const int k = node.dim;
    const float v = q[k];
    const float diff_low = v - node.low, diff_high = v - node.high;
    std::uint32_t near, far;
    float cut;
    if (diff_low + diff_high < 0) {
      near = at + 1, far = node.second;
      cut = (v - node.high) * (v - node.high);
    } else {
      near = node.second, far = at + 1;
      cut = (v - node.low) * (v - node.low);
    }
    if (!searchNode(result, q, near, cell_d2, cell, eps_factor)) return false;
    const float saved = cell[k];
    cell_d2 = cell_d2 + cut - saved;
    cell[k] = cut;
    if (cell_d2 * eps_factor <= result.bound() && !searchNode(result, q, far, cell_d2, cell, eps_factor)) return false;
    cell[k] = saved;
    return true;
  }

  float value(const float* data, std::uint32_t id, int k) const {
    return data[static_cast<std::size_t>(id) * Dim + static_cast<std::size_t>(k)];
  }

  void build(const float* data) {
    if (count_ == 0) return;
    ids_.resize(count_);
    for (std::size_t i = 0; i < count_; ++i) ids_[i] = static_cast<std::uint32_t>(i);
    for (int k = 0; k < Dim; ++k) root_[k].low = root_[k].high = data[k];
    for (std::size_t i = 1; i < count_; ++i)
      for (int k = 0; k < Dim; ++k) {
        root_[k].low = std::min(root_[k].low, data[i * Dim + k]);
        root_[k].high = std::max(root_[k].high, data[i * Dim + k]);
      }
    nodes_.reserve(2 * (count_ / (kLeafMax / 2) + 1));
    Box box = root_;
    divide(data, 0, count_, box);
    rows_.assign(count_ * kStride, 0.f);
    for (std::size_t r = 0; r < count_; ++r)
      std::copy(data + static_cast<std::size_t>(ids_[r]) * Dim, data + static_cast<std::size_t>(ids_[r]) * Dim + Dim,
                rows_.data() + r * kStride);
  }

  /// Builds the subtree over ids_[left, right); on return `box` is the bounding box of those points.
  std::uint32_t divide(const float* data, std::size_t left, std::size_t right, Box& box) {
    const auto at = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({-1, static_cast<std::uint32_t>(left), static_cast<std::uint32_t>(right), 0u, 0.f, 0.f});
    if (right - left <= kLeafMax) {
      for (int k = 0; k < Dim; ++k) box[k].low = box[k].high = value(data, ids_[left], k);
      for (std::size_t i = left + 1; i < right; ++i)
        for (int k = 0; k < Dim; ++k) {
          const float x = value(data, ids_[i], k);
          box[k].low = std::min(box[k].low, x);
          box[k].high = std::max(box[k].high, x);
        }
      return at;
    }
    int cut_dim = 0;
    float cut = 0.f;
    const std::size_t split = middleSplit(data, left, right - left, box, cut_dim, cut);
    Box left_box = box;
    left_box[cut_dim].high = cut;
    divide(data, left, left + split, left_box);
    Box right_box = box;
    right_box[cut_dim].low = cut;
    const std::uint32_t second = divide(data, left + split, right, right_box);
    Node& node = nodes_[at];
    node.dim = cut_dim;
    node.second = second;
    node.low = left_box[cut_dim].high;
    node.high = right_box[cut_dim].low;
    for (int k = 0; k < Dim; ++k) {
      box[k].low = std::min(left_box[k].low, right_box[k].low);
      box[k].high = std::max(left_box[k].high, right_box[k].high);
    }
    return at;
  }

  /// The cut of ids_[ind, ind + count): among the dimensions whose box side is (within 1e-5) the longest, the
  /// one whose points spread most; cut at the side's middle clamped to the points' range; the points
  /// partitioned around it in place. Returns the number of points that go to the first child.
  std::size_t middleSplit(const float* data, std::size_t ind, std::size_t count, const Box& box, int& cut_dim,
                          float& cut) {
    const float kEps = 0.00001f;
    float max_side = box[0].high - box[0].low;
    for (int k = 1; k < Dim; ++k) max_side = std::max(max_side, box[k].high - box[k].low);
    auto range = [&](int k, float& lo, float& hi) {
      lo = hi = value(data, ids_[ind], k);
      for (std::size_t i = 1; i < count; ++i) {
        const float x = value(data, ids_[ind + i], k);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    };
    float max_spread = -1.f, lo = 0.f, hi = 0.f;
    bool have_range = false;
    cut_dim = 0;
    for (int k = 0; k < Dim; ++k) {
      if (!(box[k].high - box[k].low > (1 - kEps) * max_side)) continue;
      float l, h;
      range(k, l, h);
      if (h - l > max_spread) cut_dim = k, max_spread = h - l, lo = l, hi = h, have_range = true;
    }
    if (!have_range) range(cut_dim, lo, hi);
    const float middle = (box[cut_dim].low + box[cut_dim].high) / 2;
    cut = middle < lo ? lo : (middle > hi ? hi : middle);
    // Two passes: values below the cut first, then values equal to it (both with the swaps nanoflann makes, so
    // that equal values are distributed identically).
    std::uint32_t* ids = ids_.data() + ind;
    const int k = cut_dim;
    std::size_t l = 0, r = count - 1;
    for (;;) {
      while (l <= r && value(data, ids[l], k) < cut) ++l;
      while (r && l <= r && value(data, ids[r], k) >= cut) --r;
      if (l > r || !r) break;
      std::swap(ids[l], ids[r]);
      ++l, --r;
    }
    const std::size_t below = l;
    r = count - 1;
    for (;;) {
      while (l <= r && value(data, ids[l], k) <= cut) ++l;
      while (r && l <= r && value(data, ids[r], k) > cut) --r;
      if (l > r || !r) break;
      std::swap(ids[l], ids[r]);
      ++l, --r;
    }
    const std::size_t not_above = l;
    if (below > count / 2) return below;
    if (not_above < count / 2) return not_above;
    return count / 2;
  }

  std::size_t count_;
  Rows rows_;
  std::vector<std::uint32_t> ids_;  ///< input index of each stored row
  std::vector<Node> nodes_;
  Box root_{};
};

}  // namespace cosmo
