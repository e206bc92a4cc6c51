// bench_scancontext_sim: precision / recall of ScanContext place recognition on synthetic multi-trial sequences
// (written by cosmo_simulate: a sequence yaml with per-robot bags and pose_inW.csv references).
//
//   bench_scancontext_sim <sequence.yaml> [more.yaml ...] [--config place_recognition.yaml] [--kf 2.0]
//                         [--max-keyframes N]
//
// Per trial: scans read from the bag (trials::Ros1ScanSource); a keyframe every `--kf` metres of reference
// motion (LiDAR pose = reference body pose * extrinsic); each keyframe scan dewarped with the reference
// (per-point times); descriptors with the configured parameters.
//   intra-robot: each keyframe searched against the robot's earlier keyframes (exclude_recent excluded);
//   inter-robot: each keyframe of robot X searched against all keyframes of robot Y, for every ordered pair
//   (the radio decides in the pipeline which scans are exchanged; here every scan is, an upper bound on the
//   number of searches).
// A detection is true when the reference positions of query and top candidate are within 5 m (and 10 m).
// Separated from bench_scancontext because it links the ROS bag glue.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/trials/trial_scans.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/bench/real_trials.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/place_recognition/revisit_evaluation.hpp"

namespace fs = std::filesystem;
using namespace cosmo;
using namespace cosmo::place_recognition;

namespace {

struct Keyframes {
  std::string robot;
  std::vector<ScanContext> descriptors;
  std::vector<Eigen::Vector3d> positions;
};

std::vector<Keyframes> loadSequence(const std::string& yaml_path, const PlaceRecognitionParams& params, double kf_m,
                                    std::size_t max_keyframes) {
  std::vector<Keyframes> out;
  for (const bench::RealTrial& trial : bench::readRealTrials(yaml_path)) {
    Keyframes kf;
    kf.robot = trial.robot;
    if (!trial.present) {
      std::printf("  trial %s: %s or %s missing, skipped\n", kf.robot.c_str(), trial.bag.c_str(),
                  trial.reference.c_str());
      continue;
    }
    trials::Ros1ScanSource reader(trial.bag.string(), trial.topic);
    Scan scan;
    std::optional<Eigen::Vector3d> last;
    std::size_t scans = 0;
    bench::Stopwatch sw;
    while (reader.next(scan) && kf.descriptors.size() < max_keyframes) {
      ++scans;
      if (!trial.body.covers(scan.stamp)) continue;
      const Pose3 lidar = trial.lidarPoseAt(scan.stamp);
      if (last && (lidar.translation() - *last).norm() <= kf_m) continue;
      last = lidar.translation();
      kf.descriptors.push_back(makeScanContext(trial.dewarped(scan), params.sc));
      kf.positions.push_back(lidar.translation());
    }
    std::printf("  trial %s: %zu scans read, %zu keyframes (%.1f s)\n", kf.robot.c_str(), scans, kf.descriptors.size(),
                sw.elapsedMs() * 1e-3);
    std::fflush(stdout);
    out.push_back(std::move(kf));
  }
  return out;
}

void printTable(const char* title, const std::vector<QueryOutcome>& outcomes, double threshold) {
  std::printf("%s: %zu queries\n", title, outcomes.size());
  for (const double radius : {5.0, 10.0}) {
    const PrPoint d = precisionRecallAt(outcomes, threshold, radius);
    std::printf(
        "  default threshold %.3f, revisit <= %.0f m: precision %.3f recall %.3f (%zu/%zu detections "
        "true, %zu revisits)\n",
        threshold, radius, d.precision, d.recall, d.true_positives, d.detections, d.revisits);
  }
  std::printf("  threshold | 5 m: det  TP  revisits precision recall | 10 m: TP revisits precision recall\n");
  for (double t = 0.05; t <= 0.601; t += 0.025) {
    const PrPoint a = precisionRecallAt(outcomes, t, 5.0), b = precisionRecallAt(outcomes, t, 10.0);
    std::printf("  %8.3f  | %6zu %4zu %6zu  %8.3f %6.3f | %7zu %6zu  %8.3f %6.3f%s\n", t, a.detections,
                a.true_positives, a.revisits, a.precision, a.recall, b.true_positives, b.revisits, b.precision,
                b.recall, std::abs(t - threshold) < 1e-9 ? "  <- default" : "");
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sequences;
  std::string config;
  double kf_m = 2.0;
  std::size_t max_keyframes = 1000000;
  cosmo::CommandLine app("bench_scancontext_sim",
                         "Precision / recall of ScanContext place recognition on synthetic multi-trial sequences, "
                         "intra- and inter-robot.");
  app.add_option("SEQUENCE.yaml", sequences, "sequences written by cosmo_simulate")->required();
  cosmo::addModuleConfig(app, config, "place recognition");
  app.add_option("--kf", kf_m, "a keyframe every this many metres of reference motion")->capture_default_str();
  app.add_option("--max-keyframes", max_keyframes, "at most this many keyframes per trial")->type_name("N");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  try {
    PlaceRecognitionParams params;
    if (!config.empty()) params = PlaceRecognitionParams::fromConfig(ConfigNode::load(config));
    const ScanContextDatabaseParams dbp = params.databaseParams();
    std::vector<QueryOutcome> intra_all, inter_all;
    for (const auto& seq : sequences) {
      std::printf("== sequence %s (keyframes every %.1f m, exclude_recent %d) ==\n", seq.c_str(), kf_m,
                  params.exclude_recent);
      const auto robots = loadSequence(seq, params, kf_m, max_keyframes);
      std::vector<QueryOutcome> intra, inter;
      for (const auto& r : robots) {
        const auto o = evaluateIncremental(r.descriptors, r.positions, dbp, params.exclude_recent);
        intra.insert(intra.end(), o.begin(), o.end());
      }
      for (const auto& x : robots)
        for (const auto& y : robots) {
          if (&x == &y) continue;
          const auto o = evaluateAgainst(x.descriptors, x.positions, y.descriptors, y.positions, dbp);
          const PrPoint d = precisionRecallAt(o, params.threshold, 5.0);
          std::printf("  inter %s -> %s: %zu queries, %zu revisits (5 m), %zu detections, %zu true\n", x.robot.c_str(),
                      y.robot.c_str(), o.size(), d.revisits, d.detections, d.true_positives);
          inter.insert(inter.end(), o.begin(), o.end());
        }
      printTable("intra-robot", intra, params.threshold);
      printTable("inter-robot", inter, params.threshold);
      intra_all.insert(intra_all.end(), intra.begin(), intra.end());
      inter_all.insert(inter_all.end(), inter.begin(), inter.end());
    }
    if (sequences.size() > 1) {
      std::printf("== all %zu sequences ==\n", sequences.size());
      printTable("intra-robot", intra_all, params.threshold);
      printTable("inter-robot", inter_all, params.threshold);
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_scancontext_sim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
