// bench_recorder: (1) time DatasetRecorder on a COSMO-sized synthetic team (adding measurements, build(),
// dumpJrl, atomic write); (2) write a single-robot run with known noise (the TUHH covariances) and show that
// the noise-model estimation recovers it (the same run can be fed to cosmo_noise_models).
//   bench_recorder [--robots 3] [--keyframes 600] [--seed 1] [--out DIR]
#include <cmath>
#include <algorithm>
#include <filesystem>
#include <optional>
#include <tuple>
#include <iomanip>
#include <iostream>
#include <random>
#include <string>

#include <Eigen/Cholesky>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/jrl/io.hpp"

using namespace cosmo;

namespace {

struct Noise {
  std::mt19937_64 rng;
  std::normal_distribution<double> normal;
  Pose3 perturb(const Pose3& truth, const Matrix6& cov) {
    Vector6 z;
    for (int i = 0; i < 6; ++i) z(i) = normal(rng);
    return truth * expSE3(Eigen::LLT<Matrix6>(cov).matrixL() * z);
  }
};

Pose3 walk(std::size_t i, std::size_t robot) {
  const double s = 0.05 * static_cast<double>(i);
  return makePose(30 * std::cos(s + robot) + 0.02 * static_cast<double>(i), 30 * std::sin(1.3 * s + robot),
                  0.5 * std::sin(s), 0.0, 0.0, s + robot + M_PI / 2);
}

constexpr StampNs kT0 = 1666284719545345152ULL;

/// (1) A team: keyframes every second, an intra-robot closure every 3rd keyframe, an inter-robot one every 4th,
/// 10 % of closures gross errors; the recorder's stages timed.
void benchTeam(std::size_t robots, std::size_t keyframes, const std::string& out, const dataset::NoiseModels& noise,
               Noise& rng) {
  std::vector<char> ids;
  for (std::size_t r = 0; r < robots; ++r) ids.push_back(static_cast<char>('a' + r));
  dataset::DatasetRecorder rec("bench_team", ids, noise);
  bench::Stopwatch sw;
  std::size_t closures = 0;
  for (std::size_t i = 0; i < keyframes; ++i) {
    for (std::size_t r = 0; r < robots; ++r) {
      const Pose3 truth = walk(i, r);
      const Pose3 odo =
          i ? rng.perturb(walk(i - 1, r).inverse(Eigen::Isometry) * truth, noise.odometry) : Pose3::Identity();
      rec.addKeyframe(ids[r], i, kT0 + i * 1000000000ULL + r * 1000, odo, truth);
      auto add = [&](std::size_t r2, std::size_t j) {
        Pose3 m = rng.perturb(truth.inverse(Eigen::Isometry) * walk(j, r2), noise.loop_closure);
        if (closures % 10 == 9) m = m * makePose(2, 1, 0, 0, 0, 0.3);
        rec.addLoopClosure(
            {ids[r], kT0 + i * 1000000000ULL + r * 1000 + 1, jrl::symbol(ids[r], i), jrl::symbol(ids[r2], j), m});
        ++closures;
      };
      if (i >= 50 && i % 3 == 0) add(r, i - 50);
      if (robots > 1 && i >= 10 && i % 4 == 0) add((r + 1) % robots, i - 10);
    }
  }
  const double add_ms = sw.elapsedMs();
  sw.restart();
  dataset::BuildReport report;
  const jrl::Dataset ds = rec.build(&report);
  const double build_ms = sw.elapsedMs();
  sw.restart();
  const std::string text = jrl::dumpJrl(ds);
  const double dump_ms = sw.elapsedMs();
  const std::string path = (std::filesystem::path(out) / "bench_team.jrl").string();
  sw.restart();
  rec.write(path);
  const double write_ms = sw.elapsedMs();
  std::cout << std::fixed << std::setprecision(1) << "team: " << robots << " robots x " << keyframes << " keyframes, "
            << closures << " loop closures (" << report.outliers << " labelled outliers), " << text.size() / 1e6
            << " MB JRL\n  add " << add_ms << " ms, build " << build_ms << " ms, dumpJrl " << dump_ms
            << " ms, write (build + dump + atomic write + metadata) " << write_ms << " ms -> " << path << "\n";
}

/// (2) A single-robot run of n keyframes with known noise, written to `path`; returns the dataset.
jrl::Dataset singleRobotRun(std::size_t n, const std::string& path, const dataset::NoiseModels& noise, Noise& rng) {
  dataset::DatasetRecorder single("bench_single_robot", {'a'}, noise);
  for (std::size_t i = 0; i < n; ++i) {
    const Pose3 truth = walk(i, 0);
    const Pose3 odo =
        i ? rng.perturb(walk(i - 1, 0).inverse(Eigen::Isometry) * truth, noise.odometry) : Pose3::Identity();
    single.addKeyframe('a', i, kT0 + i * 1000000000ULL, odo, truth);
    if (i >= 50) {
      Pose3 m = rng.perturb(truth.inverse(Eigen::Isometry) * walk(i - 50, 0), noise.loop_closure);
      if (i % 10 == 0) m = m * makePose(2, 1, 0, 0, 0, 0.3);
      single.addLoopClosure({'a', kT0 + i * 1000000000ULL, jrl::symbol('a', i), jrl::symbol('a', i - 50), m});
    }
  }
  jrl::Dataset run;
  single.write(path, &run);
  return run;
}

/// Estimated against true sigmas, per axis, for both models.
void printEstimate(const dataset::NoiseModelEstimate& est, const dataset::NoiseModels& noise) {
  for (const auto& [what, q, truth] :
       {std::tuple<const char*, Matrix6, Matrix6>{"odometry", est.models.odometry, noise.odometry},
        {"loop closure", est.models.loop_closure, noise.loop_closure}}) {
    std::cout << "  " << std::setw(12) << what << ":";
    double worst = 0;
    for (int i = 0; i < 6; ++i) {
      std::cout << ' ' << std::setprecision(3) << std::sqrt(q(i, i)) / std::sqrt(truth(i, i));
      worst = std::max(worst, std::abs(q(i, i) / truth(i, i) - 1.0));
    }
    std::cout << "  (max |var ratio - 1| " << std::setprecision(3) << worst << ", max |dQ|/max|Q| "
              << (q - truth).cwiseAbs().maxCoeff() / truth.cwiseAbs().maxCoeff() << ")\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t robots = 3, keyframes = 600;
  std::uint64_t seed = 1;
  std::string out = std::filesystem::temp_directory_path().string();
  cosmo::CommandLine app("bench_recorder",
                         "Times DatasetRecorder on a COSMO-sized synthetic team, then writes a single-robot run "
                         "with known noise and shows that the noise-model estimation recovers it.");
  app.add_option("--robots", robots, "robots of the team (1-26)")->capture_default_str();
  app.add_option("--keyframes", keyframes, "keyframes per robot")->capture_default_str();
  app.add_option("--seed", seed, "the noise's seed")->capture_default_str();
  app.add_option("--out", out, "where the datasets are written")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  robots = std::min<std::size_t>(std::max<std::size_t>(robots, 1), 26);
  const dataset::NoiseModels noise;  // TUHH covariances
  Noise rng{std::mt19937_64(seed), {}};
  benchTeam(robots, keyframes, out, noise, rng);

  const std::size_t n = 20 * keyframes;
  const std::string single_path = (std::filesystem::path(out) / "bench_single_robot.jrl").string();
  const jrl::Dataset run = singleRobotRun(n, single_path, noise, rng);
  bench::Stopwatch sw;
  const dataset::MeasurementSets sets = dataset::collectMeasurements(run);
  const dataset::NoiseModelEstimate est = estimateNoiseModels(sets.odometry, sets.loop_closures);
  const double est_ms = sw.elapsedMs();
  std::cout << "single robot: " << n << " keyframes, " << sets.loop_closures.size() << " loop closures ("
            << est.loop_closure.rejected << " over 0.5 m / 0.05 rad) -> " << single_path << "\n"
            << "  estimation " << std::setprecision(1) << est_ms
            << " ms; sigma estimated / true [rx ry rz tx ty tz]:\n";
  printEstimate(est, noise);
  return 0;
}
