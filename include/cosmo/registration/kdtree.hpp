#pragma once
// Exact kd-tree over contiguous float rows (nanoflann, single index: deterministic), for 3-D points and for
// feature vectors. The data must outlive the tree.
#include <Eigen/Core>
#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace cosmo {

template <int Dim>
class KdTree {
 public:
  /// `data` holds `count` rows of `Dim` floats (e.g. std::vector<Eigen::Vector3f>::data()->data()).
  KdTree(const float* data, std::size_t count) : adaptor_{data, count}, index_(Dim, adaptor_, params()) {
    index_.buildIndex();
  }
  std::size_t size() const { return adaptor_.count; }

  /// Nearest neighbour: (index, squared distance); (-1, inf) for an empty tree. With eps > 0 the search is
  /// (1+eps)-approximate (still deterministic).
  std::pair<int, float> nearest(const float* query, float eps = 0.f) const {
    if (adaptor_.count == 0) return {-1, std::numeric_limits<float>::infinity()};
    std::uint32_t idx = 0;
    float d2 = 0.f;
    nanoflann::KNNResultSet<float, std::uint32_t> rs(1);
    rs.init(&idx, &d2);
    index_.findNeighbors(rs, query, nanoflann::SearchParams(32, eps));
    return {static_cast<int>(idx), d2};
  }

  /// Nearest neighbour within squared distance `max_d2` (the bound prunes the search: far queries are cheap);
  /// (-1, inf) when there is none. Same answer as nearest() when that one is within the bound.
  std::pair<int, float> nearestWithin(const float* query, float max_d2) const {
    if (adaptor_.count == 0) return {-1, std::numeric_limits<float>::infinity()};
    std::uint32_t idx = 0;
    float d2 = 0.f;
    nanoflann::KNNResultSet<float, std::uint32_t> rs(1);
    rs.init(&idx, &d2);
    d2 = std::nextafter(max_d2, std::numeric_limits<float>::infinity());  // worst distance: only closer points
    index_.findNeighbors(rs, query, nanoflann::SearchParams(32, 0.f));
    if (rs.size() == 0) return {-1, std::numeric_limits<float>::infinity()};
    return {static_cast<int>(idx), d2};
  }

  /// Whether some row lies within squared distance `max_d2` (inclusive) of the query: the search stops at the
  /// first one found, so it is cheaper than nearestWithin(); the same verdict.
  bool anyWithin(const float* query, float max_d2) const {
    if (adaptor_.count == 0) return false;
    FirstHit hit{std::nextafter(max_d2, std::numeric_limits<float>::infinity())};
    index_.findNeighbors(hit, query, nanoflann::SearchParams(32, 0.f));
    return hit.found;
  }

  /// All neighbours within `radius` (unsorted order is the tree's, deterministic); returns their count.
  std::size_t radius(const float* query, float radius, std::vector<std::pair<std::uint32_t, float>>& out) const {
    out.clear();
    nanoflann::SearchParams sp;
    sp.sorted = false;
    return index_.radiusSearch(query, radius * radius, out, sp);
  }

 private:
  struct Adaptor {
    const float* data;
    std::size_t count;
    std::size_t kdtree_get_point_count() const { return count; }
    float kdtree_get_pt(std::size_t i, std::size_t d) const { return data[i * Dim + d]; }
    /// The root bounding box, in one branch-free row-major pass (the same values nanoflann's own pass finds).
    template <class BBox>
    bool kdtree_get_bbox(BBox& bb) const {
      if (count == 0) return false;
      for (int d = 0; d < Dim; ++d) bb[d].low = bb[d].high = data[d];
      for (std::size_t i = 1; i < count; ++i) {
        const float* row = data + i * Dim;
        for (int d = 0; d < Dim; ++d) {
          bb[d].low = std::min(bb[d].low, row[d]);
          bb[d].high = std::max(bb[d].high, row[d]);
        }
      }
      return true;
    }
  };
  /// Squared L2 over a whole row as one Eigen expression (SSE packets): for the high-dimensional feature rows.
  struct RowL2 {
    using ElementType = float;
    using DistanceType = float;
    const Adaptor& source;
    explicit RowL2(const Adaptor& s) : source(s) {}
    float evalMetric(const float* a, std::uint32_t b, std::size_t) const {
      using Row = Eigen::Map<const Eigen::Matrix<float, Dim, 1>>;
      return (Row(a) - Row(source.data + static_cast<std::size_t>(b) * Dim)).squaredNorm();
    }
    template <typename U, typename V>
    float accum_dist(const U a, const V b, std::size_t) const {
      return (a - b) * (a - b);
    }
  };
  using Metric = std::conditional_t<(Dim > 4), RowL2, nanoflann::L2_Simple_Adaptor<float, Adaptor>>;
  using Index = nanoflann::KDTreeSingleIndexAdaptor<Metric, Adaptor, Dim, std::uint32_t>;
  static nanoflann::KDTreeSingleIndexAdaptorParams params() {
    return nanoflann::KDTreeSingleIndexAdaptorParams(Dim > 4 ? 64 : 10);
  }

  /// nanoflann result set that accepts one point (closer than `bound`) and then ends the search.
  struct FirstHit {
    float bound;
    bool found = false;
    float worstDist() const { return bound; }
    bool full() const { return found; }
    bool addPoint(float, std::uint32_t) {
      found = true;
      return false;
    }
  };

  Adaptor adaptor_;
  Index index_;
};

}  // namespace cosmo
