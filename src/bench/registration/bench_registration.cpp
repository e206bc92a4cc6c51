// bench_registration: accuracy and speed of the global registration on the real scan pairs of
// ../shared/data/scan_snippets (issue 6), each with the source rotated by 0, 90 and 180 deg in yaw.
//   bench_registration [--config FILE] [--yaws 0,90,180] [--write-pairs FILE] [--speed-repeats N]
//                      [--dense] [--synthetic N] [--seed S]
// (a) table of pairs x yaw: errors, inliers, verdict; success = accepted and <= 0.3 m, <= 1 deg.
// (b) speed, one thread: median time per stage and per pair for KITTI (64 beams, ~120k points) and for a
//     128 x 1024-sized cloud (with --dense: each KITTI scan plus a copy of itself jittered by 2 cm, ~240k).
// (c) --synthetic N: N pairs cut from the real KITTI/MulRan scans (see syntheticPair) at 0-10 m offset and
//     random yaw (seeded), success = accepted and < 0.5 m, < 2 deg; plus the gate's false-accept rate on
//     non-overlapping real pairs.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cosmo/common/command_line.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/registration/global_registration.hpp"
#include "cosmo/bench/snippet_pairs.hpp"
#include "cosmo/registration/pair_evaluation.hpp"
#include "cosmo/bench/stage_timer.hpp"

using namespace cosmo;

namespace {

struct Run {
  std::string name;
  double dist = 0, yaw = 0;
  registration::RegistrationResult r;
  registration::PoseError e;
  std::map<std::string, double> ms;
  double total = 0;
  bool success = false;
};

Run runOne(const registration::GlobalRegistration& reg, const std::string& name, const Scan& src0, const Scan& tgt,
           const Pose3& T_expected, double yaw_deg, double max_t, double max_r) {
  const double yaw = yaw_deg * M_PI / 180.0;
  const Scan src = yaw != 0.0 ? registration::rotateScanYaw(src0, yaw) : src0;
  bench::StageTimer timer;
  timer.restart();
  Run run;
  run.name = name;
  run.dist = T_expected.translation().norm();
  run.yaw = yaw_deg;
  run.r = reg.align(src, tgt, &timer);
  run.ms = timer.milliseconds();
  run.total = timer.total();
  run.e = registration::poseError(run.r.T_target_source,
                                  T_expected * Pose3(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())).inverse());
  run.success = run.r.valid && run.e.translation_m <= max_t && run.e.rotation_deg <= max_r;
  return run;
}

void printRun(const Run& x) {
  std::printf("%-18s %6.2f %5.0f %6zu %6zu %6zu %6zu %6zu %5.2f %5.2f %4s %8.3f %8.3f %8.1f %s\n", x.name.c_str(),
              x.dist, x.yaw, x.r.source_points, x.r.correspondences, x.r.max_core_size, x.r.pruned_inliers,
              x.r.final_inliers, x.r.overlap, x.r.structure_overlap, x.r.valid ? "yes" : "no", x.e.translation_m,
              x.e.rotation_deg, x.total, x.success ? "OK" : "FAIL");
  std::fflush(stdout);
}

void printHeader() {
  std::printf("%-18s %6s %5s %6s %6s %6s %6s %6s %5s %5s %4s %8s %8s %8s %s\n", "pair", "dist_m", "yaw", "srcpts",
              "corr", "core", "clique", "final", "ovl", "sovl", "acc", "err_m", "err_deg", "ms", "result");
}

void printSpeed(const std::string& label, const std::vector<Run>& runs) {
  if (runs.empty()) return;
  std::printf("\n(b) speed, one thread, %s: %zu pair runs, median ms per stage (per pair: both clouds' features)\n",
              label.c_str(), runs.size());
  double pts = 0;
  for (const auto& r : runs) pts += static_cast<double>(r.r.source_points);
  for (const char* s : bench::kRegistrationStages) {
    std::vector<double> v;
    for (const auto& r : runs) {
      const auto it = r.ms.find(s);
      v.push_back(it == r.ms.end() ? 0.0 : it->second);
    }
    std::printf("  %-10s %8.1f\n", s, bench::quantile(v, 0.5));
  }
  std::vector<double> tot;
  for (const auto& r : runs) tot.push_back(r.total);
  std::printf("  %-10s %8.1f  (p90 %.1f; mean feature points per cloud %.0f)\n", "TOTAL", bench::quantile(tot, 0.5),
              bench::quantile(tot, 0.9), pts / static_cast<double>(runs.size()));
}

Scan densify(const Scan& s, std::mt19937_64& rng) {
  Scan out = s;
  std::normal_distribution<float> n(0.f, 0.02f);
  for (const auto& p : s.points) out.points.push_back(p + Eigen::Vector3f(n(rng), n(rng), n(rng)));
  out.intensity.clear();
  return out;
}

/// A synthetic loop pair cut from one real scan (used by --synthetic when no simulator is at hand): a virtual
/// source sensor `offset` m from the real one (direction `dir`) with heading `yaw`; target = the scan's points
/// within `keep` m (horizontal) of the real sensor, source = the points within `keep` m of the virtual sensor
/// expressed in its frame; 2 cm Gaussian noise and an independent random 20 % drop for each.
struct SynthPair {
  Scan source, target;
  Pose3 T_target_source;
};
SynthPair syntheticPair(const Scan& scan, double offset, double yaw, double dir, double keep, std::mt19937_64& rng) {
  SynthPair p;
  const Eigen::Vector3d c(offset * std::cos(dir), offset * std::sin(dir), 0.0);
  p.T_target_source = Pose3::Identity();
  p.T_target_source.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  p.T_target_source.translation() = c;
  const Pose3 T_source_target = p.T_target_source.inverse();
  std::normal_distribution<float> noise(0.f, 0.02f);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& q : scan.points) {
    const Eigen::Vector3d qd = q.cast<double>();
    if (qd.head<2>().norm() <= keep && u(rng) > 0.2)
      p.target.points.push_back(q + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
    if ((qd - c).head<2>().norm() <= keep && u(rng) > 0.2)
      p.source.points.push_back((T_source_target * qd).cast<float>() +
                                Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
  }
  return p;
}

struct Options {
  std::string config_path, write_pairs;
  std::vector<double> yaws{0, 90, 180};
  int speed_repeats = 1, synthetic = 0;
  bool dense = false;
  std::uint64_t seed = 7;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  cosmo::CommandLine app("bench_registration",
                         "Accuracy and speed of the global registration on the real scan pairs, each with the source "
                         "rotated in yaw: (a) errors, inliers, verdict per pair and yaw; (b) speed per stage and "
                         "pair, one thread; (c) with --synthetic, pairs cut from the real scans and the gate's "
                         "false-accept rate.");
  cosmo::addModuleConfig(app, o.config_path, "registration");
  app.add_option("--yaws", o.yaws, "source yaw rotations, degrees, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--write-pairs", o.write_pairs, "write the pair list (cosmo_register --pairs) to FILE")
      ->type_name("FILE");
  app.add_option("--speed-repeats", o.speed_repeats, "runs per timed pair (0: no speed section)")
      ->capture_default_str();
  app.add_flag("--dense", o.dense, "also time each KITTI scan plus a jittered copy of itself (~240k points)");
  app.add_option("--synthetic", o.synthetic, "N pairs cut from the real scans at 0-10 m offset and random yaw")
      ->type_name("N");
  app.add_option("--seed", o.seed, "the synthetic pairs' seed")->capture_default_str();
  return app.parseOrExit(argc, argv);
}

/// Scan files read once.
class ScanCache {
 public:
  const Scan& load(const std::string& f) {
    auto it = cache_.find(f);
    if (it == cache_.end()) it = cache_.emplace(f, readScanFile(f)).first;
    return it->second;
  }

 private:
  std::map<std::string, Scan> cache_;
};

bool isKitti(const registration::ScanPair& p) { return p.name.rfind("kitti", 0) == 0; }

/// (a) accuracy on the real pairs at every yaw; returns the KITTI runs (for the speed figures).
std::vector<Run> realPairs(const registration::GlobalRegistration& reg,
                           const std::vector<registration::ScanPair>& pairs, const std::vector<double>& yaws,
                           ScanCache& scans) {
  std::printf("(a) real pairs, success = accepted and error <= 0.3 m and <= 1 deg\n");
  printHeader();
  std::vector<Run> kitti_runs;
  int near_ok = 0, near_n = 0, far_ok = 0, far_n = 0;
  for (const auto& p : pairs) {
    for (const double yaw : yaws) {
      const Run x = runOne(reg, p.name, scans.load(p.source), scans.load(p.target), p.T_target_source, yaw, 0.3, 1.0);
      printRun(x);
      if (isKitti(p)) kitti_runs.push_back(x);
      (p.distance_m <= 10.0 ? near_n : far_n)++;
      (p.distance_m <= 10.0 ? near_ok : far_ok) += x.success;
    }
  }
  std::printf("pairs <= 10 m: %d / %d succeeded; farther (17-19 m): %d / %d\n", near_ok, near_n, far_ok, far_n);
  return kitti_runs;
}

/// (b) speed: the KITTI pairs (repeated), and with --dense each KITTI scan plus a jittered copy of itself.
void speed(const registration::GlobalRegistration& reg, const std::vector<registration::ScanPair>& pairs,
           const Options& o, std::vector<Run> kitti_runs, ScanCache& scans) {
  for (int rep = 1; rep < o.speed_repeats; ++rep)
    for (const auto& p : pairs)
      if (isKitti(p))
        kitti_runs.push_back(
            runOne(reg, p.name, scans.load(p.source), scans.load(p.target), p.T_target_source, 0, 0.3, 1.0));
  printSpeed("KITTI HDL-64E (64 beams, ~120k points)", kitti_runs);
  if (!o.dense) return;
  std::mt19937_64 rng(o.seed);
  std::vector<Run> dense_runs;
  std::size_t n_points = 0;
  for (const auto& p : pairs) {
    if (!isKitti(p)) continue;
    const Scan s = densify(scans.load(p.source), rng), t = densify(scans.load(p.target), rng);
    n_points = s.size();
    dense_runs.push_back(runOne(reg, p.name, s, t, p.T_target_source, 0, 0.3, 1.0));
  }
  printSpeed("128x1024-sized (KITTI + jittered copy, " + std::to_string(n_points) + " points)", dense_runs);
}

/// (c) synthetic loop pairs cut from the real scans.
void syntheticPairs(const registration::GlobalRegistration& reg, const std::vector<registration::ScanPair>& pairs,
                    int synthetic, std::uint64_t seed, ScanCache& scans) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::string> bases;
  for (const auto& p : pairs) bases.push_back(p.target);
  int ok = 0, accepted = 0;
  std::printf(
      "\n(c) %d synthetic pairs (crop 40 m radius around two virtual sensors 0-10 m apart in one real scan,"
      " random yaw, 2 cm noise, 20 %% drop), success = accepted and < 0.5 m, < 2 deg\n",
      synthetic);
  for (int k = 0; k < synthetic; ++k) {
    const std::string& base = bases[static_cast<std::size_t>(k) % bases.size()];
    const double off = 10.0 * u(rng), yaw = 2 * M_PI * u(rng), dir = 2 * M_PI * u(rng);
    const SynthPair sp = syntheticPair(scans.load(base), off, yaw, dir, 40.0, rng);
    const Run x = runOne(reg, "synth" + std::to_string(k), sp.source, sp.target, sp.T_target_source, 0, 0.5, 2.0);
    ok += x.success;
    accepted += x.r.valid;
    if (!x.success) printRun(x);
  }
  std::printf("synthetic success: %d / %d (%.1f %%), accepted %d\n", ok, synthetic, 100.0 * ok / synthetic, accepted);
}

/// (c') the gate on non-overlapping real pairs: different places of KITTI 00 (>= 80 m apart) and different
/// datasets.
void nonOverlappingPairs(const registration::GlobalRegistration& reg, const std::string& root, ScanCache& scans) {
  const std::string k = root + "/kitti00/velodyne/";
  const std::string m = root + "/mulran_kaist03_keyframes/Scans/";
  const std::string h = root + "/hdl32_pair/";
  const std::vector<std::pair<std::string, std::string>> neg = {
      {k + "000000.bin", k + "000094.bin"},    {k + "000000.bin", k + "000198.bin"},
      {k + "000094.bin", k + "000198.bin"},    {k + "000040.bin", k + "000198.bin"},
      {k + "000020.bin", k + "000094.bin"},    {k + "000040.bin", k + "000094.bin"},
      {k + "000001.bin", k + "000199.bin"},    {k + "000095.bin", k + "000199.bin"},
      {m + "000000.pcd", k + "000000.bin"},    {m + "000010.pcd", k + "000094.bin"},
      {m + "000020.pcd", h + "251370668.pcd"}, {h + "251371071.pcd", k + "000198.bin"},
      {m + "000000.pcd", m + "000020.pcd"}};
  std::printf("\n(c') gate on non-overlapping real pairs (different places / datasets), yaw 0 and 90\n");
  printHeader();
  int acc = 0, n = 0;
  for (const auto& [s, t] : neg)
    for (const double yaw : {0.0, 90.0}) {
      const Run x =
          runOne(reg, std::filesystem::path(s).stem().string() + "/" + std::filesystem::path(t).stem().string(),
                 scans.load(s), scans.load(t), Pose3::Identity(), yaw, 0.0, 0.0);
      printRun(x);
      acc += x.r.valid;
      ++n;
    }
  std::printf("false accepts: %d / %d (%.1f %%)\n", acc, n, 100.0 * acc / n);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
  const auto root = cosmo::sharedPath("data/scan_snippets");
  if (!root) {
    std::printf("../shared/data/scan_snippets not found (set COSMO_SHARED_DIR): nothing to measure\n");
    return 0;
  }
  const registration::RegistrationParams params =
      o.config_path.empty() ? registration::RegistrationParams{}
                            : registration::RegistrationParams::fromConfig(ConfigNode::load(o.config_path));
  const registration::GlobalRegistration reg(params);
  const auto pairs = bench::snippetPairs(*root, true);
  if (!o.write_pairs.empty()) {
    writePairList(o.write_pairs, pairs);
    std::printf("wrote %zu pairs to %s\n", pairs.size(), o.write_pairs.c_str());
    return 0;
  }
  ScanCache scans;
  speed(reg, pairs, o, realPairs(reg, pairs, o.yaws, scans), scans);
  if (o.synthetic > 0) syntheticPairs(reg, pairs, o.synthetic, o.seed, scans);
  nonOverlappingPairs(reg, *root, scans);
  return 0;
}
