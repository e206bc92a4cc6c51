// cosmo_register: global registration of a scan pair (no initial guess), KISS-Matcher style.
//   cosmo_register SOURCE TARGET [--yaw DEG] [--expected FILE|"x y z qx qy qz qw"] [--config FILE]
//   cosmo_register --pairs LIST [--yaw DEG] [--config FILE]
// Prints the transform T_target_source, inlier counts per stage, the gate's verdict, time per stage and, with an
// expected transform, the translation / rotation errors. Success = accepted by the gate and within
// --max-trans (m, default 0.3) and --max-rot (deg, default 1).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cosmo/common/command_line.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/registration/global_registration.hpp"
#include "cosmo/registration/pair_evaluation.hpp"
#include "cosmo/bench/stage_timer.hpp"

using namespace cosmo;

namespace {

std::optional<Pose3> parseExpected(const std::string& arg) {
  std::istringstream ss(arg);
  std::vector<double> v;
  for (double x; ss >> x;) v.push_back(x);
  if (ss.eof() && !v.empty()) return parsePoseNumbers(v, "--expected");
  return readMatrixPose(arg);
}

std::string poseString(const Pose3& T) {
  const Eigen::Quaterniond q(T.linear());
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.4f %.4f %.4f %.6f %.6f %.6f %.6f", T.translation().x(), T.translation().y(),
                T.translation().z(), q.x(), q.y(), q.z(), q.w());
  return buf;
}

struct Outcome {
  registration::RegistrationResult result;
  std::map<std::string, double> ms;
  double total_ms = 0.0;
  std::optional<registration::PoseError> error;
};

Outcome runPair(const registration::GlobalRegistration& reg, const std::string& src_file, const std::string& tgt_file,
                double yaw_deg, const std::optional<Pose3>& expected) {
  Scan src = readScanFile(src_file);
  const Scan tgt = readScanFile(tgt_file);
  const double yaw = yaw_deg * M_PI / 180.0;
  if (yaw != 0.0) src = registration::rotateScanYaw(src, yaw);
  bench::StageTimer timer;
  timer.restart();
  Outcome o;
  o.result = reg.align(src, tgt, &timer);
  o.ms = timer.milliseconds();
  o.total_ms = timer.total();
  if (expected) {
    const Pose3 Rz(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    o.error = registration::poseError(o.result.T_target_source, *expected * Rz.inverse());
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> positional;
  std::string config_path, expected_arg, pairs_path;
  double yaw_deg = 0.0, max_trans = 0.3, max_rot = 1.0;
  cosmo::CommandLine app("cosmo_register",
                         "Global registration of a scan pair (no initial guess), KISS-Matcher style: prints the "
                         "transform T_target_source, inlier counts per stage, the gate's verdict, time per stage "
                         "and, with an expected transform, the errors.");
  positional.resize(2);
  app.add_option("SOURCE", positional[0], "the source scan (without --pairs)");
  app.add_option("TARGET", positional[1], "the target scan");
  app.add_option("--pairs", pairs_path,
                 "a list of pairs instead, lines: source target [x y z qx qy qz qw | 12/16 matrix numbers | 4x4 file]")
      ->type_name("LIST");
  app.add_option("--yaw", yaw_deg, "rotate the source about z first, degrees")->capture_default_str();
  app.add_option("--expected", expected_arg, "the true transform: a 4x4 file or \"x y z qx qy qz qw\"")
      ->type_name("FILE|\"x y z qx qy qz qw\"");
  cosmo::addModuleConfig(app, config_path, "registration");
  app.add_option("--max-trans", max_trans, "success: accepted and translation error within M")->capture_default_str();
  app.add_option("--max-rot", max_rot, "success: accepted and rotation error within DEG")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  if (pairs_path.empty() && (positional[0].empty() || positional[1].empty())) {
    std::cerr << "cosmo_register: give SOURCE TARGET or --pairs LIST\nRun with --help for more information.\n";
    return 2;
  }
  try {
    const registration::RegistrationParams params =
        config_path.empty() ? registration::RegistrationParams{}
                            : registration::RegistrationParams::fromConfig(cosmo::ConfigNode::load(config_path));
    const registration::GlobalRegistration reg(params);

    if (!pairs_path.empty()) {
      const auto pairs = registration::readPairList(pairs_path);
      std::printf("%-28s %7s %6s %6s %6s %6s %5s %8s %8s %8s %s\n", "pair", "dist_m", "corr", "core", "clique", "final",
                  "valid", "err_m", "err_deg", "time_ms", "result");
      int ok = 0;
      for (const auto& p : pairs) {
        const Outcome o = runPair(reg, p.source, p.target, yaw_deg, p.T_target_source);
        const bool success = o.result.valid && o.error->translation_m <= max_trans && o.error->rotation_deg <= max_rot;
        ok += success;
        std::printf("%-28s %7.2f %6zu %6zu %6zu %6zu %5s %8.3f %8.3f %8.1f %s\n", p.name.c_str(), p.distance_m,
                    o.result.correspondences, o.result.max_core_size, o.result.pruned_inliers, o.result.final_inliers,
                    o.result.valid ? "yes" : "no", o.error->translation_m, o.error->rotation_deg, o.total_ms,
                    success ? "OK" : "FAIL");
      }
      std::printf("success: %d / %zu (%.1f %%), criterion: accepted and error <= %.2f m, %.2f deg, yaw %.1f deg\n", ok,
                  pairs.size(), pairs.empty() ? 0.0 : 100.0 * ok / pairs.size(), max_trans, max_rot, yaw_deg);
      return 0;
    }

    std::optional<Pose3> expected;
    if (!expected_arg.empty()) expected = parseExpected(expected_arg);
    const Outcome o = runPair(reg, positional[0], positional[1], yaw_deg, expected);
    const auto& r = o.result;
    std::printf("T_target_source (x y z qx qy qz qw): %s\n", poseString(r.T_target_source).c_str());
    std::cout << "matrix:\n" << r.T_target_source.matrix() << "\n";
    std::printf("points (feature): source %zu, target %zu\n", r.source_points, r.target_points);
    std::printf("correspondences %zu -> max k-core %zu -> %s %zu -> final inliers %zu\n", r.correspondences,
                r.max_core_size,
                params.use_max_clique ? (r.clique_proven ? "max clique" : "clique (budget hit)") : "k-core",
                r.pruned_inliers, r.final_inliers);
    std::printf("hypotheses verified %d, reported #%d (0 = the maximum clique)\n", r.hypotheses, r.hypothesis);
    std::printf("refined: %s, overlap %.3f, structure overlap %.3f\n", r.refined ? "yes" : "no", r.overlap,
                r.structure_overlap);
    std::printf("verdict: %s (%s)\n", r.valid ? "ACCEPTED" : "REJECTED", r.reason.c_str());
    std::printf("time (ms):");
    for (const char* s : bench::kRegistrationStages) {
      const auto it = o.ms.find(s);
      std::printf(" %s %.1f", s, it == o.ms.end() ? 0.0 : it->second);
    }
    std::printf(" | total %.1f\n", o.total_ms);
    if (o.error)
      std::printf(
          "error vs expected: %.4f m, %.4f deg -> %s\n", o.error->translation_m, o.error->rotation_deg,
          (r.valid && o.error->translation_m <= max_trans && o.error->rotation_deg <= max_rot) ? "SUCCESS" : "FAILURE");
    return r.valid ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "cosmo_register: " << e.what() << "\n";
    return 2;
  }
}
