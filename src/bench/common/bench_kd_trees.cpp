// bench_kd_trees: why the project keeps more than one k-d tree. Each tree is timed on the workload it serves
// and on the other's, on the same data:
//   LOAM's local map: a tree over ~3 scans of points, rebuilt every scan, asked for the k = 5 nearest points
//     within a distance bound (common/kd_tree3.hpp KdTree3, against common/kd_tree.hpp KdTree<3> via a
//     radius search + partial sort, and nanoflann 1.4's knnSearch);
//   registration's feature matching: 33-D rows, the (1+eps)-approximate nearest neighbour
//     (common/kd_tree.hpp KdTree<33>, against nanoflann 1.4).
//
//   bench_kd_trees [--repeats N]
//
// Input: sweeps of the built-in synthetic street (testing/street_scene.hpp), deterministic. Prints the
// median wall time per build and per query batch, and checks that the trees agree on the answers.
#include <nanoflann.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/kd_tree3.hpp"
#include "cosmo/test_support/sim_scenes.hpp"
#include "cosmo/common/kd_tree.hpp"

using namespace cosmo;

namespace {

/// nanoflann's dataset interface over rows of `Dim` floats.
struct FloatRows {
  const float* data = nullptr;
  std::size_t rows = 0;
  int dim = 3;
  std::size_t kdtree_get_point_count() const { return rows; }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return data[i * dim + d]; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};
template <int Dim>
using NanoTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, FloatRows>, FloatRows, Dim, std::uint32_t>;

/// Points of sweeps of the synthetic street taken 1 m apart (the sensor driving along +x).
std::vector<Eigen::Vector3f> streetPoints(int first_sweep, int sweeps, int keep_every) {
  const sim::World scene = test_support::streetWorld();
  const sim::LidarModel lidar = test_support::idealLidar();
  std::vector<Eigen::Vector3f> out;
  for (int s = first_sweep; s < first_sweep + sweeps; ++s) {
    const double x = 10.0 + s;
    const Scan scan = test_support::simulateSweep(scene, lidar, 1'000'000'000LL * (s + 1),
                                                  [x](double) { return Pose3(Eigen::Translation3d(x, 0.0, 0.0)); });
    for (std::size_t i = 0; i < scan.size(); i += keep_every)
      out.push_back(scan.points[i] + Eigen::Vector3f(static_cast<float>(x), 0.f, 0.f));
  }
  return out;
}

struct Timing {
  std::vector<double> build, query;
  void print(const char* what, std::size_t queries) const {
    std::printf("  %-46s build %7.2f ms   %zu queries %8.2f ms  (%.2f us/query)\n", what, bench::quantile(build, 0.5),
                queries, bench::quantile(query, 0.5), 1e3 * bench::quantile(query, 0.5) / queries);
  }
};

void loamWorkload(int repeats) {
  const auto map = streetPoints(0, 3, 6);      // three scans' worth of points, thinned as LOAM's features are
  const auto queries = streetPoints(3, 1, 8);  // the next scan's
  const int k = 5;
  const float max_dist = 4.0f;
  std::printf("LOAM local map: %zu points, %zu queries, k = %d within %.0f m\n", map.size(), queries.size(), k,
              max_dist);
  std::vector<Eigen::Vector3d> map_d(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) map_d[i] = map[i].cast<double>();

  Timing own, reg, nano;
  std::size_t checksum_own = 0, checksum_reg = 0, checksum_nano = 0;
  for (int r = 0; r < repeats; ++r) {
    {
      bench::Stopwatch sw;
      KdTree3 tree;
      tree.build(map_d);
      own.build.push_back(sw.elapsedMs());
      sw.restart();
      std::vector<std::size_t> idx;
      std::size_t sum = 0;
      for (const auto& q : queries) {
        tree.knn(q.cast<double>(), k, max_dist, idx);
        sum += idx.size();
      }
      own.query.push_back(sw.elapsedMs());
      checksum_own = sum;
    }
    {
      bench::Stopwatch sw;
      KdTree<3> tree(map.data()->data(), map.size());
      reg.build.push_back(sw.elapsedMs());
      sw.restart();
      std::vector<std::pair<std::uint32_t, float>> within;
      std::size_t sum = 0;
      for (const auto& q : queries) {
        tree.radius(q.data(), max_dist, within);
        const std::size_t n = std::min<std::size_t>(k, within.size());
        std::partial_sort(within.begin(), within.begin() + n, within.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; });
        sum += n;
      }
      reg.query.push_back(sw.elapsedMs());
      checksum_reg = sum;
    }
    {
      FloatRows rows{map.data()->data(), map.size(), 3};
      bench::Stopwatch sw;
      NanoTree<3> tree(3, rows, nanoflann::KDTreeSingleIndexAdaptorParams(10));
      tree.buildIndex();
      nano.build.push_back(sw.elapsedMs());
      sw.restart();
      std::uint32_t idx[5];
      float d2[5];
      std::size_t sum = 0;
      for (const auto& q : queries) {
        const std::size_t n = tree.knnSearch(q.data(), k, idx, d2);
        for (std::size_t i = 0; i < n; ++i) sum += d2[i] <= max_dist * max_dist ? 1 : 0;
      }
      nano.query.push_back(sw.elapsedMs());
      checksum_nano = sum;
    }
  }
  own.print("odometry KdTree3 (k nearest within the bound)", queries.size());
  reg.print("registration KdTree<3> (radius + partial sort)", queries.size());
  nano.print("nanoflann 1.4 knnSearch (then the bound)", queries.size());
  std::printf("  neighbours found: %zu / %zu / %zu%s\n", checksum_own, checksum_reg, checksum_nano,
              checksum_own == checksum_reg && checksum_reg == checksum_nano ? " (agree)" : " (DIFFER)");
}

void featureWorkload(int repeats) {
  const int dim = 33, rows = 5000, queries = 5000;
  std::mt19937 rng(7);
  std::gamma_distribution<float> bin(0.6f, 10.f);  // FPFH-like: non-negative, skewed histogram bins
  std::vector<float> data(static_cast<std::size_t>(rows) * dim), query(static_cast<std::size_t>(queries) * dim);
  for (auto& v : data) v = bin(rng);
  for (std::size_t i = 0; i < query.size(); ++i) query[i] = data[i] + std::normal_distribution<float>(0.f, 2.f)(rng);
  const float eps = 10.f;
  std::printf("registration feature matching: %d rows x %d-D, %d queries, (1+%g)-approximate nearest\n", rows, dim,
              queries, eps);
  Timing reg, nano;
  bool agree = true;
  for (int r = 0; r < repeats; ++r) {
    std::vector<int> a(queries), b(queries);
    {
      bench::Stopwatch sw;
      KdTree<33> tree(data.data(), rows);
      reg.build.push_back(sw.elapsedMs());
      sw.restart();
      for (int q = 0; q < queries; ++q) a[q] = tree.nearest(&query[static_cast<std::size_t>(q) * dim], eps).first;
      reg.query.push_back(sw.elapsedMs());
    }
    {
      FloatRows fr{data.data(), static_cast<std::size_t>(rows), dim};
      bench::Stopwatch sw;
      NanoTree<33> tree(dim, fr, nanoflann::KDTreeSingleIndexAdaptorParams(64));
      tree.buildIndex();
      nano.build.push_back(sw.elapsedMs());
      sw.restart();
      nanoflann::SearchParams params;
      params.eps = eps;
      for (int q = 0; q < queries; ++q) {
        std::uint32_t idx;
        float d2;
        nanoflann::KNNResultSet<float, std::uint32_t> res(1);
        res.init(&idx, &d2);
        tree.findNeighbors(res, &query[static_cast<std::size_t>(q) * dim], params);
        b[q] = static_cast<int>(idx);
      }
      nano.query.push_back(sw.elapsedMs());
    }
    agree = agree && a == b;
  }
  reg.print("registration KdTree<33>", queries);
  nano.print("nanoflann 1.4", queries);
  std::printf("  answers: %s\n", agree ? "identical" : "DIFFER");
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  cosmo::CommandLine app("bench_kd_trees",
                         "Each k-d tree timed on the workload it serves and on the other's, on the same data; "
                         "checks that the trees agree on the answers.");
  app.add_option("--repeats", repeats, "runs per figure (at least 1)")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  repeats = std::max(1, repeats);
  loamWorkload(repeats);
  featureWorkload(repeats);
  return 0;
}
