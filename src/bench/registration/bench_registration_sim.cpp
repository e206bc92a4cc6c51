// bench_registration_sim: global registration on synthetic loop pairs from DIFFERENT trials of a simulated
// sequence (written by cosmo_simulate: a sequence yaml with per-robot bags and pose_inW.csv references).
//
//   bench_registration_sim <sequence.yaml> [--config registration.yaml] [--pairs N] [--negatives N]
//                          [--kf 2.0] [--max-offset 10] [--min-separation 100] [--seed S] [--cache FILE]
//
// Keyframes every --kf m of reference motion per trial, dewarped with the reference (per-point times). Loop pairs:
// keyframes of two different robots whose reference LiDAR positions are within --max-offset m, sampled uniformly
// (seeded); the source is rotated by a random yaw. Success = accepted by the gate and error < 0.5 m and < 2 deg
// against the reference relative pose. Non-overlapping pairs: keyframes of different robots more than
// --min-separation m apart; a gate acceptance there is a false accept. Separate from bench_registration
// because it links the ROS bag glue. --cache FILE: keyframes (poses and dewarped points) are read from FILE when it
// exists, else read from the bags and written there (reading a long sequence's bags takes minutes).
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cosmo/trials/trial_scans.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/bench/real_trials.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/registration/global_registration.hpp"
#include "cosmo/registration/pair_evaluation.hpp"
#include "cosmo/bench/stage_timer.hpp"

namespace fs = std::filesystem;
using namespace cosmo;

namespace {

struct Keyframe {
  int robot = 0;
  Pose3 pose;  // reference LiDAR pose
  Scan scan;   // dewarped
};

std::vector<Keyframe> loadKeyframes(const std::string& yaml_path, double kf_m) {
  std::vector<Keyframe> out;
  int robot = 0;
  for (const bench::RealTrial& trial : bench::readRealTrials(yaml_path)) {
    if (!trial.present) throw std::runtime_error(trial.bag.string() + " or " + trial.reference.string() + " missing");
    trials::Ros1ScanSource reader(trial.bag.string(), trial.topic);
    Scan scan;
    std::optional<Eigen::Vector3d> last;
    std::size_t n = 0;
    while (reader.next(scan)) {
      if (!trial.body.covers(scan.stamp)) continue;
      const Pose3 lidar = trial.lidarPoseAt(scan.stamp);
      if (last && (lidar.translation() - *last).norm() <= kf_m) continue;
      last = lidar.translation();
      out.push_back({robot, lidar, trial.dewarped(scan)});
      ++n;
    }
    std::printf("  trial %s: %zu keyframes\n", trial.robot.c_str(), n);
    ++robot;
  }
  return out;
}

constexpr std::uint64_t kCacheMagic = 0x31666b6f6d736f63ULL;  // "cosmokf1"

/// Keyframe cache: magic, kf spacing, count, then per keyframe robot, 16 pose numbers, point count, points.
bool readCache(const std::string& path, double kf_m, std::vector<Keyframe>& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::uint64_t magic = 0, n = 0;
  double kf = 0;
  in.read(reinterpret_cast<char*>(&magic), sizeof magic);
  in.read(reinterpret_cast<char*>(&kf), sizeof kf);
  in.read(reinterpret_cast<char*>(&n), sizeof n);
  if (!in || magic != kCacheMagic || kf != kf_m) return false;
  out.resize(n);
  for (auto& k : out) {
    std::int32_t robot = 0;
    std::uint64_t np = 0;
    Eigen::Matrix4d m;
    in.read(reinterpret_cast<char*>(&robot), sizeof robot);
    in.read(reinterpret_cast<char*>(m.data()), sizeof(double) * 16);
    in.read(reinterpret_cast<char*>(&np), sizeof np);
    k.robot = robot;
    k.pose.matrix() = m;
    k.scan.points.resize(np);
    in.read(reinterpret_cast<char*>(k.scan.points.data()), static_cast<std::streamsize>(sizeof(float) * 3 * np));
  }
  return static_cast<bool>(in);
}

void writeCache(const std::string& path, double kf_m, const std::vector<Keyframe>& kfs) {
  std::ofstream out(path, std::ios::binary);
  const std::uint64_t n = kfs.size();
  out.write(reinterpret_cast<const char*>(&kCacheMagic), sizeof kCacheMagic);
  out.write(reinterpret_cast<const char*>(&kf_m), sizeof kf_m);
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  for (const auto& k : kfs) {
    const std::int32_t robot = k.robot;
    const std::uint64_t np = k.scan.points.size();
    const Eigen::Matrix4d m = k.pose.matrix();
    out.write(reinterpret_cast<const char*>(&robot), sizeof robot);
    out.write(reinterpret_cast<const char*>(m.data()), sizeof(double) * 16);
    out.write(reinterpret_cast<const char*>(&np), sizeof np);
    out.write(reinterpret_cast<const char*>(k.scan.points.data()),
              static_cast<std::streamsize>(sizeof(float) * 3 * np));
  }
}

struct Options {
  std::string seq, config, cache;
  int n_pairs = 100, n_neg = 50;
  double kf_m = 2.0, max_offset = 10.0, min_sep = 100.0;
  std::uint64_t seed = 1;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  cosmo::CommandLine app("bench_registration_sim",
                         "Global registration on synthetic loop pairs from different trials of a simulated sequence, "
                         "and the gate's false accepts on non-overlapping pairs.");
  app.add_option("SEQUENCE.yaml", o.seq, "a sequence written by cosmo_simulate")->required();
  cosmo::addModuleConfig(app, o.config, "registration");
  app.add_option("--pairs", o.n_pairs, "loop pairs")->capture_default_str();
  app.add_option("--negatives", o.n_neg, "non-overlapping pairs")->capture_default_str();
  app.add_option("--kf", o.kf_m, "a keyframe every this many metres of reference motion")->capture_default_str();
  app.add_option("--max-offset", o.max_offset, "loop pairs: reference LiDAR positions within this, m")
      ->capture_default_str();
  app.add_option("--min-separation", o.min_sep, "non-overlapping pairs: more than this apart, m")
      ->capture_default_str();
  app.add_option("--seed", o.seed, "the pairs' seed")->capture_default_str();
  app.add_option("--cache", o.cache,
                 "keyframes are read from FILE when it exists, else read from the bags and written there")
      ->type_name("FILE");
  return app.parseOrExit(argc, argv);
}

/// The keyframes, from the cache when it holds them, else from the bags (then written to the cache).
std::vector<Keyframe> keyframes(const Options& o) {
  std::vector<Keyframe> kfs;
  if (o.cache.empty() || !readCache(o.cache, o.kf_m, kfs)) {
    kfs = loadKeyframes(o.seq, o.kf_m);
    if (!o.cache.empty()) writeCache(o.cache, o.kf_m, kfs);
  } else {
    std::printf("  %zu keyframes from the cache %s\n", kfs.size(), o.cache.c_str());
  }
  return kfs;
}

using Pairs = std::vector<std::pair<int, int>>;

/// Keyframe pairs of different robots: `near` within max_offset, `far` beyond min_separation; shuffled (seeded)
/// and cut to their counts.
void samplePairs(const std::vector<Keyframe>& kfs, const Options& o, std::mt19937_64& rng, Pairs& near, Pairs& far) {
  for (std::size_t i = 0; i < kfs.size(); ++i)
    for (std::size_t j = 0; j < kfs.size(); ++j) {
      if (kfs[i].robot == kfs[j].robot || i == j) continue;
      const double d = (kfs[i].pose.translation() - kfs[j].pose.translation()).norm();
      if (d <= o.max_offset) near.emplace_back(static_cast<int>(i), static_cast<int>(j));
      if (d > o.min_sep) far.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  std::shuffle(near.begin(), near.end(), rng);
  std::shuffle(far.begin(), far.end(), rng);
  if (static_cast<int>(near.size()) > o.n_pairs) near.resize(static_cast<std::size_t>(o.n_pairs));
  if (static_cast<int>(far.size()) > o.n_neg) far.resize(static_cast<std::size_t>(o.n_neg));
}

/// The loop pairs, each with the source rotated by a random yaw: a line per pair, then the success by offset.
void loopPairs(const registration::GlobalRegistration& reg, const std::vector<Keyframe>& kfs, const Pairs& near,
               double max_offset, std::mt19937_64& rng, std::uniform_real_distribution<double>& u) {
  std::printf(
      "loop pairs (different robots, <= %.0f m apart, random yaw): %zu; success = accepted and < 0.5 m, "
      "< 2 deg\n",
      max_offset, near.size());
  std::printf("%-10s %6s %7s %6s %6s %6s %5s %5s %4s %8s %8s %7s\n", "pair", "dist", "yaw", "corr", "clique", "final",
              "ovl", "sovl", "acc", "err_m", "err_deg", "cpu_ms");
  int ok = 0, acc = 0;
  std::vector<double> ms;
  int bins_ok[3] = {0, 0, 0}, bins_n[3] = {0, 0, 0};
  for (const auto& [s, t] : near) {
    const double yaw = u(rng);
    const Pose3 Rz(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    const Pose3 expected = kfs[t].pose.inverse() * kfs[s].pose * Rz.inverse();
    bench::StageTimer timer;
    timer.restart();
    const registration::RegistrationResult r =
        reg.align(registration::rotateScanYaw(kfs[s].scan, yaw), kfs[t].scan, &timer);
    ms.push_back(timer.total());
    const registration::PoseError e = registration::poseError(r.T_target_source, expected);
    const bool success = r.valid && e.translation_m < 0.5 && e.rotation_deg < 2.0;
    const double d = (kfs[s].pose.translation() - kfs[t].pose.translation()).norm();
    const int b = d < 3.0 ? 0 : (d < 6.0 ? 1 : 2);
    bins_n[b]++, bins_ok[b] += success;
    ok += success, acc += r.valid;
    std::printf("%4d-%-5d %6.2f %7.1f %6zu %6zu %6zu %5.2f %5.2f %4s %8.3f %8.3f %7.1f %s\n", s, t, d, yaw * 180 / M_PI,
                r.correspondences, r.pruned_inliers, r.final_inliers, r.overlap, r.structure_overlap,
                r.valid ? "yes" : "no", e.translation_m, e.rotation_deg, timer.total(), success ? "OK" : "FAIL");
    std::fflush(stdout);
  }
  std::printf(
      "success: %d / %zu (%.1f %%), accepted %d; by offset 0-3 m %d/%d, 3-6 m %d/%d, 6-10 m %d/%d; "
      "median cpu %.1f ms\n",
      ok, near.size(), near.empty() ? 0.0 : 100.0 * ok / near.size(), acc, bins_ok[0], bins_n[0], bins_ok[1], bins_n[1],
      bins_ok[2], bins_n[2], bench::quantile(ms, 0.5));
}

/// The non-overlapping pairs: what the gate saw, and its false accepts.
void farPairs(const registration::GlobalRegistration& reg, const std::vector<Keyframe>& kfs, const Pairs& far,
              double min_sep, std::mt19937_64& rng, std::uniform_real_distribution<double>& u) {
  int false_acc = 0;
  std::vector<double> neg_final, neg_overlap, neg_structure;
  for (const auto& [s, t] : far) {
    const registration::RegistrationResult r = reg.align(registration::rotateScanYaw(kfs[s].scan, u(rng)), kfs[t].scan);
    false_acc += r.valid;
    neg_final.push_back(static_cast<double>(r.final_inliers));
    neg_overlap.push_back(r.overlap);
    neg_structure.push_back(r.structure_overlap);
    if (r.valid)
      std::printf("  false accept %d-%d: %.0f m apart, final inliers %zu\n", s, t,
                  (kfs[s].pose.translation() - kfs[t].pose.translation()).norm(), r.final_inliers);
  }
  std::printf(
      "non-overlapping pairs: final inliers median %.0f max %.0f; overlap median %.2f max %.2f; "
      "structure overlap median %.2f max %.2f\n",
      bench::quantile(neg_final, 0.5), bench::quantile(neg_final, 1.0), bench::quantile(neg_overlap, 0.5),
      bench::quantile(neg_overlap, 1.0), bench::quantile(neg_structure, 0.5), bench::quantile(neg_structure, 1.0));
  std::printf("non-overlapping pairs (> %.0f m apart): %d / %zu accepted by the gate (false-accept rate %.1f %%)\n",
              min_sep, false_acc, far.size(), far.empty() ? 0.0 : 100.0 * false_acc / far.size());
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
  try {
    const registration::RegistrationParams params =
        o.config.empty() ? registration::RegistrationParams{}
                         : registration::RegistrationParams::fromConfig(ConfigNode::load(o.config));
    const registration::GlobalRegistration reg(params);
    std::printf("== %s ==\n", o.seq.c_str());
    const std::vector<Keyframe> kfs = keyframes(o);
    Pairs near, far;
    std::mt19937_64 rng(o.seed);
    samplePairs(kfs, o, rng, near, far);
    std::uniform_real_distribution<double> u(-M_PI, M_PI);
    loopPairs(reg, kfs, near, o.max_offset, rng, u);
    farPairs(reg, kfs, far, o.min_sep, rng, u);
  } catch (const std::exception& e) {
    std::cerr << "bench_registration_sim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
