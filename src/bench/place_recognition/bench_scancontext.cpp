// bench_scancontext: ScanContext accuracy on real scans, speed, and precision / recall on synthetic sequences.
//
//   bench_scancontext [--real] [--speed] [--sim <sequence.yaml> ...] [--config place_recognition.yaml]
//                     [--repeat N]
// Without a part selected, runs --real and --speed. Real data come from ../shared/data/scan_snippets
// (COSMO_SHARED_DIR overrides). One thread throughout; wall-clock times, so run it on an idle machine.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <time.h>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/place_recognition/revisit_evaluation.hpp"
#include "cosmo/test_support/sim_scenes.hpp"

using namespace cosmo;
using namespace cosmo::place_recognition;

namespace {

/// CPU time of this thread, ms: less disturbed than wall time when other processes share the cores.
class CpuStopwatch {
 public:
  CpuStopwatch() { restart(); }
  void restart() { start_ = now(); }
  double elapsedMs() const { return now() - start_; }

 private:
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
  }
  double start_ = 0.0;
};

double deg(double rad) { return rad * 180.0 / M_PI; }
double wrapAngle(double a) { return std::remainder(a, 2.0 * M_PI); }

struct Stats {
  std::vector<double> v;
  void add(double x) { v.push_back(x); }
  double mean() const { return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / v.size(); }
  double min() const { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }
  double max() const { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
  double q(double p) const { return bench::quantile(v, p); }
};

Scan turnSensor(const Scan& scan, double yaw) {
  Scan out = scan;
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(-yaw), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& p : out.points) p = R * p;
  return out;
}

struct RealSet {
  std::string name;
  std::vector<Scan> scans;
  std::vector<Pose3> poses;  // LiDAR poses
  std::vector<std::size_t> ids;
};

std::optional<RealSet> loadMulran() {
  const auto dir = sharedPath("data/scan_snippets/mulran_kaist03_keyframes");
  if (!dir) return std::nullopt;
  RealSet s;
  s.name = "MulRan KAIST03 keyframes";
  const auto poses = readKittiPoses(*dir + "/optimized_poses.txt");
  const auto files = listScanFiles(*dir + "/Scans");
  for (std::size_t i = 0; i < files.size(); ++i) {
    s.scans.push_back(readScanFile(files[i]));
    s.poses.push_back(poses.at(i));
    s.ids.push_back(i);
  }
  return s;
}

std::optional<RealSet> loadKitti() {
  const auto dir = sharedPath("data/scan_snippets/kitti00");
  if (!dir) return std::nullopt;
  RealSet s;
  s.name = "KITTI 00 frames";
  const auto poses = kittiPosesToLidar(readKittiPoses(*dir + "/poses.txt"), readKittiCalibTr(*dir + "/calib.txt"));
  for (const auto& f : listScanFiles(*dir + "/velodyne")) {
    const std::size_t id = std::stoul(f.substr(f.find_last_of('/') + 1, 6));
    s.scans.push_back(readScanFile(f));
    s.poses.push_back(poses.at(id));
    s.ids.push_back(id);
  }
  return s;
}

/// Near vs far pair distances, and the yaw estimate on rotated copies, for one real set.
void realNearFar(const RealSet& set, const PlaceRecognitionParams& params, double near_m, double far_m) {
  std::vector<ScanContext> sc;
  for (const auto& s : set.scans) sc.push_back(makeScanContext(s, params.sc));
  Stats near, far;
  for (std::size_t i = 0; i < sc.size(); ++i)
    for (std::size_t j = i + 1; j < sc.size(); ++j) {
      const double sep = (set.poses[i].translation() - set.poses[j].translation()).norm();
      const double d =
          scanContextDistance(sc[j], sc[i], params.sc.empty_columns, params.sc.coarse_search_radius).distance;
      if (sep <= near_m) near.add(d);
      if (sep >= far_m) far.add(d);
    }
  std::printf("  %-26s near pairs (<= %.0f m): n=%3zu distance mean %.3f [min %.3f, max %.3f]\n", set.name.c_str(),
              near_m, near.v.size(), near.mean(), near.min(), near.max());
  std::printf("  %-26s far pairs  (>= %.0f m): n=%3zu distance mean %.3f [min %.3f, max %.3f]  -> %s\n", "", far_m,
              far.v.size(), far.mean(), far.min(), far.max(),
              near.v.empty() || far.v.empty() ? "n/a"
              : near.max() < far.min()        ? "separated (max near < min far)"
                                              : "overlapping");
}

/// Yaw estimate for (a) a scan vs its rotated copy, (b) a near pair with one scan rotated (ground truth: the
/// reference relative yaw plus the applied turn).
void realYaw(const RealSet& set, const PlaceRecognitionParams& params, double near_m) {
  const std::vector<double> turns = {0.0, 0.1, 0.5, 1.0, 1.5708, 2.0, 2.5, 3.1416, -0.3, -1.2, -2.2, -2.9};
  const double sector = 2.0 * M_PI / params.sc.sectors;
  Stats self_err, pair_err;
  int self_within = 0, pair_within = 0;
  for (std::size_t i = 0; i < set.scans.size(); ++i) {
    const ScanContext cand = makeScanContext(set.scans[i], params.sc);
    for (const double t : turns) {
      const auto m = scanContextDistance(makeScanContext(turnSensor(set.scans[i], t), params.sc), cand,
                                         params.sc.empty_columns, params.sc.coarse_search_radius);
      const double e = std::abs(wrapAngle(m.yaw - t));
      self_err.add(deg(e));
      self_within += e <= sector + 1e-9;
    }
    for (std::size_t j = 0; j < set.scans.size(); ++j) {
      if (j == i) continue;
      const Pose3 rel = set.poses[i].inverse() * set.poses[j];  // T_i_j: query j relative to candidate i
      if (rel.translation().norm() > near_m) continue;
      for (const double t : turns) {
        const auto m = scanContextDistance(makeScanContext(turnSensor(set.scans[j], t), params.sc), cand,
                                           params.sc.empty_columns, params.sc.coarse_search_radius);
        const double e = std::abs(wrapAngle(m.yaw - (yawOf(rel) + t)));
        pair_err.add(deg(e));
        pair_within += e <= sector + 1e-9;
      }
    }
  }
  std::printf("  %-26s rotated copy: %zu cases, |yaw error| mean %.2f deg, max %.2f deg, %d within one sector\n",
              set.name.c_str(), self_err.v.size(), self_err.mean(), self_err.max(), self_within);
  std::printf(
      "  %-26s rotated near pair (<= %.0f m): %zu cases, |yaw error| mean %.2f deg, p95 %.2f, max %.2f, "
      "%d within one sector\n",
      "", near_m, pair_err.v.size(), pair_err.mean(), pair_err.q(0.95), pair_err.max(), pair_within);
}

/// Full shift search vs coarse sector-key alignment, and point_stride vs full resolution, on real pairs.
void realSearchVariants(const RealSet& set, const PlaceRecognitionParams& params, double near_m) {
  std::vector<ScanContext> sc;
  for (const auto& s : set.scans) sc.push_back(makeScanContext(s, params.sc));
  for (const int radius : {1, 3, 6}) {
    int same = 0, total = 0;
    Stats increase;
    for (std::size_t i = 0; i < sc.size(); ++i)
      for (std::size_t j = 0; j < sc.size(); ++j) {  // near pairs and each scan with itself, rotated copies
        if ((set.poses[i].translation() - set.poses[j].translation()).norm() > near_m) continue;
        for (const double t : {0.0, 1.0, 2.5, -1.7}) {
          const ScanContext q = t == 0.0 ? sc[j] : makeScanContext(turnSensor(set.scans[j], t), params.sc);
          const auto full = scanContextDistance(q, sc[i], params.sc.empty_columns, -1);
          const auto coarse = scanContextDistance(q, sc[i], params.sc.empty_columns, radius);
          same += full.shift == coarse.shift;
          ++total;
          increase.add(coarse.distance - full.distance);
        }
      }
    std::printf(
        "  %-26s coarse alignment +-%d sectors: same shift as full search in %d/%d near (<= 3 m) or "
        "self pairs with turns, distance increase mean %.4f max %.4f\n",
        set.name.c_str(), radius, same, total, increase.mean(), increase.max());
  }
  for (const int stride : {2, 4, 8}) {
    PlaceRecognitionParams p = params;
    p.sc.point_stride = stride;
    Stats self, near, far;
    for (std::size_t i = 0; i < set.scans.size(); ++i) {
      const ScanContext thin = makeScanContext(set.scans[i], p.sc);
      self.add(scanContextDistance(thin, sc[i], p.sc.empty_columns).distance);
      for (std::size_t j = i + 1; j < set.scans.size(); ++j) {
        const double sep = (set.poses[i].translation() - set.poses[j].translation()).norm();
        const double d = scanContextDistance(makeScanContext(set.scans[j], p.sc), thin, p.sc.empty_columns).distance;
        if (sep <= near_m) near.add(d);
        if (sep >= 15.0) far.add(d);
      }
    }
    std::printf(
        "  %-26s point_stride %d: distance to the full-resolution descriptor mean %.3f max %.3f; near "
        "mean %.3f max %.3f, far mean %.3f min %.3f\n",
        "", stride, self.mean(), self.max(), near.mean(), near.max(), far.mean(), far.min());
  }
}

void runReal(const PlaceRecognitionParams& params) {
  std::printf("== (a) real scans ==\n");
  const auto mulran = loadMulran();
  const auto kitti = loadKitti();
  if (!mulran && !kitti) {
    std::printf("  ../shared/data/scan_snippets not found: real-data part not measured\n");
    return;
  }
  for (const auto* set : {mulran ? &*mulran : nullptr, kitti ? &*kitti : nullptr}) {
    if (!set) continue;
    realNearFar(*set, params, 3.0, 15.0);
    realYaw(*set, params, 3.0);
    realSearchVariants(*set, params, 3.0);
  }
}

/// A random-ish descriptor: occupancy falling with the ring, heights 0-15 m, as a real descriptor roughly.
ScanContext randomDescriptor(const ScanContextParams& p, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  ScanContext sc;
  sc.descriptor = Eigen::MatrixXf::Zero(p.rings, p.sectors);
  const float base = 0.3f + 0.7f * u(rng);
  for (int r = 0; r < p.rings; ++r) {
    const float occ = base * (1.0f - static_cast<float>(r) / p.rings);
    for (int s = 0; s < p.sectors; ++s)
      if (u(rng) < occ) sc.descriptor(r, s) = 0.2f + 15.0f * u(rng) * u(rng);
  }
  sc.ring_key = (sc.descriptor.array() > 0.0f).cast<float>().rowwise().sum() / static_cast<float>(p.sectors);
  sc.sector_key = sc.descriptor.colwise().mean().transpose();
  return sc;
}

void runSpeed(const PlaceRecognitionParams& params, int repeat) {
  std::printf("== (b) speed, one thread (wall clock; run on an idle machine) ==\n");
  for (const int beams : {64, 128}) {
    const Scan scan = test_support::campusScan(beams);
    for (const int stride : {1, 2, 4}) {
      ScanContextParams p = params.sc;
      p.point_stride = stride;
      std::vector<double> ms, cpu;
      ScanContext sc;
      for (int k = 0; k < repeat; ++k) {
        bench::Stopwatch sw;
        CpuStopwatch cw;
        sc = makeScanContext(scan, p);
        cpu.push_back(cw.elapsedMs());
        ms.push_back(sw.elapsedMs());
      }
      std::printf(
          "  descriptor %3dx1024 (%6zu points) point_stride %d: wall median %.3f ms p95 %.3f ms | "
          "thread CPU median %.3f ms\n",
          beams, scan.size(), stride, bench::quantile(ms, 0.5), bench::quantile(ms, 0.95), bench::quantile(cpu, 0.5));
    }
  }
  {
    std::mt19937_64 rng(5);
    const ScanContext a = randomDescriptor(params.sc, rng), b = randomDescriptor(params.sc, rng);
    for (const int radius : {-1, 3}) {
      double sink = 0.0;
      const int n = 5000;
      bench::Stopwatch sw;
      CpuStopwatch cw;
      for (int k = 0; k < n; ++k) sink += scanContextDistance(a, b, params.sc.empty_columns, radius).distance;
      std::printf("  full distance (%s): wall %.1f us, thread CPU %.1f us per call (checksum %.3f)\n",
                  radius < 0 ? "all 60 shifts" : "sector-key alignment +-3", sw.elapsedMs() * 1000.0 / n,
                  cw.elapsedMs() * 1000.0 / n, sink);
    }
  }
  for (const std::size_t n : {1000u, 10000u, 50000u}) {
    std::mt19937_64 rng(n);
    ScanContextDatabase db(params.databaseParams());
    bench::Stopwatch fill;
    std::vector<double> insert_ms;
    for (std::size_t i = 0; i < n; ++i) {
      ScanContext sc = randomDescriptor(params.sc, rng);
      bench::Stopwatch sw;
      db.insert(i, std::move(sc));
      insert_ms.push_back(sw.elapsedMs());
    }
    std::vector<double> query_ms, query_cpu;
    for (int k = 0; k < 300; ++k) {
      const ScanContext q = randomDescriptor(params.sc, rng);
      bench::Stopwatch sw;
      CpuStopwatch cw;
      const auto m = db.query(q);
      query_cpu.push_back(cw.elapsedMs());
      query_ms.push_back(sw.elapsedMs());
      if (m.empty()) std::printf("  (no match?)\n");
    }
    double insert_total = 0.0;
    for (double v : insert_ms) insert_total += v;
    std::printf(
        "  database %5zu entries (%zu in the k-d tree): query (%d candidates) wall median %.3f ms p95 %.3f "
        "ms | thread CPU median %.3f ms; insert mean (rebuilds included) %.4f ms, max %.2f ms\n",
        n, db.indexedSize(), params.num_candidates, bench::quantile(query_ms, 0.5), bench::quantile(query_ms, 0.95),
        bench::quantile(query_cpu, 0.5), insert_total / n, bench::quantile(insert_ms, 1.0));
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool real = false, speed = false;
  std::vector<std::string> sims;
  std::string config;
  int repeat = 50;
  cosmo::CommandLine app("bench_scancontext",
                         "ScanContext accuracy on real scans, speed, and precision / recall on synthetic sequences. "
                         "Without a part selected, runs --real and --speed.");
  app.add_flag("--real", real, "accuracy on the real scan snippets");
  app.add_flag("--speed", speed, "descriptor and query times");
  app.add_option("--sim", sims, "synthetic sequences")->type_name("SEQUENCE.yaml")->allow_extra_args(false);
  cosmo::addModuleConfig(app, config, "place recognition");
  app.add_option("--repeat", repeat, "runs per timed figure")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  if (!real && !speed && sims.empty()) real = speed = true;
  try {
    PlaceRecognitionParams params;
    if (!config.empty()) params = PlaceRecognitionParams::fromConfig(ConfigNode::load(config));
    if (real) runReal(params);
    if (speed) runSpeed(params, repeat);
    if (!sims.empty()) std::printf("== (c) synthetic sequences: not built into this binary yet ==\n");
  } catch (const std::exception& e) {
    std::cerr << "bench_scancontext: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
