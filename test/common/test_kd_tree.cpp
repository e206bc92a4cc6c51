// The own kd-tree (kd_tree.hpp) against nanoflann 1.4, whose tree and search it reimplements: the same answers,
// bit for bit (index and squared distance), for 33-D feature-like rows with many ties and zeros (exact and
// (1+eps)-approximate) and for 3-D points (nearest, nearest within a bound, any within, radius lists in order).
#include <gtest/gtest.h>

#include <nanoflann.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "cosmo/common/kd_tree.hpp"

using namespace cosmo;

namespace {

/// nanoflann over contiguous rows, set up as the registration used it before (leaves of 10 / 64 rows, the
/// whole-row Eigen metric for the features).
template <int Dim>
struct Reference {
  struct Adaptor {
    const float* data;
    std::size_t count;
    std::size_t kdtree_get_point_count() const { return count; }
    float kdtree_get_pt(std::size_t i, std::size_t d) const { return data[i * Dim + d]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox& bb) const {
      for (int d = 0; d < Dim; ++d) bb[d].low = bb[d].high = data[d];
      for (std::size_t i = 1; i < count; ++i)
        for (int d = 0; d < Dim; ++d) {
          bb[d].low = std::min(bb[d].low, data[i * Dim + d]);
          bb[d].high = std::max(bb[d].high, data[i * Dim + d]);
        }
      return true;
    }
  };
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
  Adaptor adaptor;
  Index index;
  Reference(const float* data, std::size_t n)
      : adaptor{data, n}, index(Dim, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(Dim > 4 ? 64 : 10)) {
    index.buildIndex();
  }
  std::pair<int, float> nearest(const float* q, float eps, float bound = -1.f) const {
    std::uint32_t idx = 0;
    float d2 = 0.f;
    nanoflann::KNNResultSet<float, std::uint32_t> rs(1);
    rs.init(&idx, &d2);
    if (bound >= 0.f) d2 = std::nextafter(bound, std::numeric_limits<float>::infinity());
    index.findNeighbors(rs, q, nanoflann::SearchParams(32, eps));
    if (bound >= 0.f && rs.size() == 0) return {-1, std::numeric_limits<float>::infinity()};
    return {static_cast<int>(idx), d2};
  }
};

/// Histogram-like rows: each 11-value block sums to 100 over a few non-zero bins, values rounded to a coarse
/// grid so that equal coordinates and equal distances occur.
std::vector<float> featureRows(std::size_t n, std::mt19937& rng) {
  std::vector<float> rows(n * 33, 0.f);
  std::uniform_int_distribution<int> bin(0, 10), spread(1, 4), weight(1, 8);
  for (std::size_t i = 0; i < n; ++i)
    for (int b = 0; b < 3; ++b) {
      const int k = spread(rng);
      std::vector<int> w(11, 0);
      int total = 0;
      for (int j = 0; j < k; ++j) {
        const int c = weight(rng);
        w[static_cast<std::size_t>(bin(rng))] += c;
        total += c;
      }
      for (int j = 0; j < 11; ++j)
        rows[i * 33 + static_cast<std::size_t>(b * 11 + j)] = std::round(100.f * w[j] / total / 2.5f) * 2.5f;
    }
  return rows;
}

}  // namespace

TEST(KdTree, FeatureRowsMatchNanoflann) {
  std::mt19937 rng(11);
  for (const std::size_t n : {1u, 50u, 700u, 4000u}) {
    const std::vector<float> data = featureRows(n, rng);
    const std::vector<float> queries = featureRows(600, rng);
    const KdTree<33> tree(data.data(), n);
    const Reference<33> ref(data.data(), n);
    for (const float eps : {0.f, 2.f, 5.f, 10.f}) {
      std::size_t same = 0, total = 0;
      auto check = [&](const float* q) {
        const auto a = tree.nearest(q, eps), b = ref.nearest(q, eps);
        ++total;
        same += a.first == b.first && a.second == b.second;
      };
      for (std::size_t i = 0; i < 600; ++i) check(&queries[i * 33]);
      for (std::size_t i = 0; i < n; i += 7) check(&data[i * 33]);  // exact duplicates of stored rows
      EXPECT_EQ(same, total) << "n " << n << " eps " << eps;
    }
  }
}

TEST(KdTree, PointsMatchNanoflann) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-20.f, 20.f);
  for (const std::size_t n : {1u, 9u, 300u, 18000u}) {
    std::vector<float> data(n * 3);
    for (std::size_t i = 0; i < n * 3; ++i) data[i] = i % 5 == 0 ? std::round(u(rng)) * 0.3f : u(rng);
    const KdTree<3> tree(data.data(), n);
    const Reference<3> ref(data.data(), n);
    std::vector<std::pair<std::uint32_t, float>> got, want;
    std::size_t same = 0, total = 0;
    for (int k = 0; k < 2000; ++k) {
      const float q[3] = {u(rng), u(rng), k % 3 == 0 ? data[(static_cast<std::size_t>(k) % n) * 3 + 2] : u(rng)};
      const float bound = k % 2 ? 0.81f : 4.f;
      const auto a = tree.nearest(q), b = ref.nearest(q, 0.f);
      const auto c = tree.nearestWithin(q, bound), d = ref.nearest(q, 0.f, bound);
      const bool any_ref = d.first >= 0;
      tree.radius(q, 2.f, got);
      nanoflann::SearchParams sp;
      sp.sorted = false;
      ref.index.radiusSearch(q, 4.f, want, sp);
      total += 4;
      same += a == b;
      same += c == d;
      same += tree.anyWithin(q, bound) == any_ref;
      same += got == want;
    }
    EXPECT_EQ(same, total) << "n " << n;
  }
  const KdTree<3> empty(nullptr, 0);
  const float q[3] = {0.f, 0.f, 0.f};
  EXPECT_EQ(empty.nearest(q).first, -1);
  EXPECT_FALSE(empty.anyWithin(q, 1.f));
}
