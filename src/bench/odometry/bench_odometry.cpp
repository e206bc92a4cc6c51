// bench_odometry: accuracy of the LOAM odometry on real scan snippets (../shared/data/scan_snippets), speed per
// scan (real KITTI HDL-64 scans, synthetic 64x1024 and 128x1024 sweeps) and drift on synthetic trials.
//
//   bench_odometry [--config config/odometry.yaml] [--repeat N] [--only abcd]
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/odometry/dewarp.hpp"
#include "cosmo/odometry/local_feature_map.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/odometry/scan_lines.hpp"
#include "cosmo/test_support/sim_scenes.hpp"
#include "cosmo/odometry/trajectory_metrics.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {
constexpr double kRadToDeg = 180.0 / M_PI;

/// CPU time of this thread (ms): the speed figure, less sensitive than the wall clock to other processes.
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}
std::vector<double> g_wall_ms;  ///< wall-clock times matching the CPU times collected by runOdometry

std::string kittiScan(const std::string& dir, int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.bin", frame);
  return dir + "/velodyne/" + name;
}

struct StepError {
  double t_cm, r_deg, gt_m;
};

StepError stepError(const Pose3& est, const Pose3& gt) {
  return {odometry::translationError(est, gt) * 100.0, odometry::rotationErrorRad(est, gt) * kRadToDeg,
          gt.translation().norm()};
}

void printStep(const std::string& what, const StepError& e, double t_target_cm, double r_target_deg,
               const std::string& note = "") {
  std::cout << "  " << std::left << std::setw(34) << what << std::right << std::fixed << std::setprecision(2) << "gt "
            << std::setw(6) << e.gt_m << " m   err " << std::setw(7) << e.t_cm << " cm  " << std::setprecision(3)
            << std::setw(6) << e.r_deg << " deg   "
            << ((e.t_cm <= t_target_cm && e.r_deg <= r_target_deg) ? "ok" : "MISS") << note << "\n";
}

/// Odometry over `scans` (stamped 0.1 s apart); returns the poses.
std::vector<Pose3> runOdometry(const std::vector<Scan>& scans, const odometry::LoamParams& params,
                               std::vector<double>* times_ms,
                               std::vector<odometry::OdometryResult>* results = nullptr) {
  odometry::LoamOdometry odom(params);
  std::vector<Pose3> poses;
  for (const Scan& s : scans) {
    bench::Stopwatch sw;
    const double cpu0 = threadCpuMs();
    const odometry::OdometryResult r = odom.update(s);
    const double ms = threadCpuMs() - cpu0;
    if (times_ms && !poses.empty()) {  // the first scan only builds the map
      times_ms->push_back(ms);
      g_wall_ms.push_back(sw.elapsedMs());
    }
    poses.push_back(r.pose);
    if (results) results->push_back(r);
  }
  return poses;
}

void sectionReal(const odometry::LoamParams& params, std::vector<double>& kitti_times, int repeat) {
  std::cout << "\n== (a) real scans (../shared/data/scan_snippets) ==\n";
  // KITTI 00.
  if (auto dir = sharedPath("data/scan_snippets/kitti00")) {
    const auto ref = kittiPosesToLidar(readKittiPoses(*dir + "/poses.txt"), readKittiCalibTr(*dir + "/calib.txt"));
    std::cout << "KITTI 00 (HDL-64E), targets <= 5 cm and <= 0.2 deg per step:\n";
    // Stretches where poses.txt repeats the same step to a millimetre (a GPS/INS gap filled at constant
    // velocity): a step inside one is compared with the fill, not with the car's motion.
    const auto fills = odometry::findConstantMotionRuns(ref);
    std::cout << "  poses.txt moves at a perfectly constant velocity (steps equal within 2 mm / 0.005 deg, >= 10 "
                 "steps: interpolated) over frames";
    for (const auto& f : fills)
      std::cout << " " << f.first << "-" << f.last << " (" << std::setprecision(3) << f.step_m << " m, " << f.step_deg
                << " deg)";
    std::cout << "\n";
    auto fillNote = [&](int a, int b) -> std::string {
      for (const auto& f : fills)
        if (static_cast<std::size_t>(a) >= f.first && static_cast<std::size_t>(b) <= f.last)
          return "  (reference interpolated here: frames " + std::to_string(f.first) + "-" + std::to_string(f.last) +
                 ")";
      return "";
    };
    for (const std::vector<int>& chain : {std::vector<int>{0, 1, 2}, {94, 95}, {198, 199}}) {
      std::vector<Scan> scans;
      for (int f : chain) {
        scans.push_back(readScanFile(kittiScan(*dir, f)));
        scans.back().stamp = toStampNs(1.0 + 0.1 * f);
      }
      std::vector<Pose3> poses;
      for (int r = 0; r < repeat; ++r) poses = runOdometry(scans, params, &kitti_times);
      for (std::size_t i = 1; i < chain.size(); ++i) {
        const Pose3 est = poses[i - 1].inverse() * poses[i];
        const Pose3 gt = ref[chain[i - 1]].inverse() * ref[chain[i]];
        printStep("frame " + std::to_string(chain[i - 1]) + " -> " + std::to_string(chain[i]), stepError(est, gt), 5.0,
                  0.2, fillNote(chain[i - 1], chain[i]));
      }
    }
  } else {
    std::cout << "KITTI 00: not measured (../shared/data/scan_snippets/kitti00 missing)\n";
  }
  // hdl32 pair.
  if (auto dir = sharedPath("data/scan_snippets/hdl32_pair")) {
    std::vector<Scan> scans{readScanFile(*dir + "/251370668.pcd"), readScanFile(*dir + "/251371071.pcd")};
    scans[0].stamp = toStampNs(1.0);
    scans[1].stamp = toStampNs(1.1);
    const auto poses = runOdometry(scans, params, nullptr);
    const Pose3 gt = readMatrixPose(*dir + "/relative.txt");
    const Pose3 gt2 = readMatrixPose(*dir + "/T_target_source_small_gicp.txt");
    std::cout << "hdl32 pair (unordered PCD, lines from elevation), targets <= 3 cm and <= 0.2 deg:\n";
    printStep("vs relative.txt (fast_gicp)", stepError(poses[1], gt), 3.0, 0.2);
    printStep("vs small_gicp's T_target_source", stepError(poses[1], gt2), 3.0, 0.2);
  } else {
    std::cout << "hdl32 pair: not measured (missing)\n";
  }
  // KITTI 07 keyframes (downsampled xyz, 3-12 m apart) and MulRan keyframes (downsampled, unordered).
  auto keyframePairs = [&](const std::string& name, const std::vector<std::string>& files,
                           const std::vector<Pose3>& ref_poses, std::size_t max_pairs) {
    std::cout << name << " (consecutive keyframes, fresh odometry per pair, zero-motion start + yaw search):\n";
    std::size_t ok = 0, n = 0;
    for (std::size_t i = 0; i + 1 < files.size() && i + 1 < ref_poses.size() && n < max_pairs; ++i, ++n) {
      std::vector<Scan> scans{readScanFile(files[i]), readScanFile(files[i + 1])};
      scans[0].stamp = toStampNs(1.0);
      scans[1].stamp = toStampNs(1.1);
      std::vector<odometry::OdometryResult> res;
      const auto poses = runOdometry(scans, params, nullptr, &res);
      const Pose3 gt = ref_poses[i].inverse() * ref_poses[i + 1];
      const StepError e = stepError(poses[1], gt);
      printStep(std::to_string(i) + " -> " + std::to_string(i + 1) + (res[1].ok ? "" : " (warn)"), e, 10.0, 0.5);
      if (e.t_cm <= 10.0 && e.r_deg <= 0.5) ++ok;
    }
    std::cout << "  within 10 cm / 0.5 deg: " << ok << " of " << n << "\n";
  };
  if (auto dir = sharedPath("data/scan_snippets/kitti07_keyframes")) {
    std::vector<Pose3> ref;
    std::ifstream in(*dir + "/graph.txt");
    std::string tag;
    double x, y, z, qx, qy, qz, qw;
    while (in >> tag >> x >> y >> z >> qx >> qy >> qz >> qw)
      ref.push_back(makePose(Eigen::Vector3d(x, y, z), Eigen::Quaterniond(qw, qx, qy, qz)));
    keyframePairs("KITTI 07 keyframes", listScanFiles(*dir), ref, 10);
  }
  if (auto dir = sharedPath("data/scan_snippets/mulran_kaist03_keyframes")) {
    keyframePairs("MulRan KAIST03 keyframes (reference = SC-A-LOAM estimate)", listScanFiles(*dir + "/Scans"),
                  readKittiPoses(*dir + "/optimized_poses.txt"), 20);
  }
}

/// Moves every point of `scan` to the frame at its stamp along constant-velocity motion `delta` over `period`
/// (the sweep's start-to-end motion).
void deskewScanConstantVelocity(Scan& scan, const Pose3& delta, double period) {
  std::vector<Eigen::Vector3d> pts(scan.points.size()), out;
  for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = scan.points[i].cast<double>();
  odometry::deskewConstantVelocity(pts, scan.time, delta, period, out);
  for (std::size_t i = 0; i < out.size(); ++i) scan.points[i] = out[i].cast<float>();
}

/// How a sweep reaches the odometry: with its point times (the odometry deskews it), or already dewarped and
/// without times: with the true motion (a perfect deskew), or with the true sweep motion at constant velocity (the
/// odometry's own deskew model, fed the true start and end poses instead of its estimates).
enum class TruthDewarp { kNone, kTrueMotion, kTrueConstantVelocity };

/// A synthetic trial: the sensor drives / walks along the street (gentle S-curve, small pitch / roll sway),
/// sweeps with motion distortion. Returns scans and the sensor pose at each stamp.
void syntheticTrial(const sim::LidarModel& lidar, double speed, double yaw_rate_amp, int n_scans, std::uint64_t seed,
                    std::vector<Scan>& scans, std::vector<Pose3>& gt, bool walking,
                    TruthDewarp truth_dewarp = TruthDewarp::kNone) {
  const sim::World scene = test_support::streetWorld(speed * n_scans * lidar.period() + 60.0, 9.0);
  auto pose_at_abs = [&](double t) {
    const double x = speed * t;
    const double y = 2.0 * std::sin(2.0 * M_PI * t / 20.0) * (yaw_rate_amp > 0 ? 1.0 : 0.0);
    const double dy = 2.0 * (2.0 * M_PI / 20.0) * std::cos(2.0 * M_PI * t / 20.0) * (yaw_rate_amp > 0 ? 1.0 : 0.0);
    const double yaw = std::atan2(dy, speed);
    const double bob = walking ? 0.03 * std::sin(2.0 * M_PI * 1.8 * t) : 0.0;
    const double roll = walking ? 0.02 * std::sin(2.0 * M_PI * 0.9 * t) : 0.0;
    const double pitch = walking ? 0.02 * std::sin(2.0 * M_PI * 1.8 * t + 0.5) : 0.0;
    return makePose(x, y, bob, roll, pitch, yaw);
  };
  for (int k = 0; k < n_scans; ++k) {
    const double t_end = 0.1 + lidar.period() * k;
    scans.push_back(test_support::simulateSweep(
        scene, lidar, toStampNs(1.0 + t_end), [&](double dt) { return pose_at_abs(t_end + dt); }, seed));
    if (truth_dewarp == TruthDewarp::kTrueMotion)
      scans.back() = odometry::dewarp(scans.back(), [&](StampNs st) { return pose_at_abs(toSeconds(st) - 1.0); });
    if (truth_dewarp == TruthDewarp::kTrueConstantVelocity)
      deskewScanConstantVelocity(scans.back(), pose_at_abs(t_end - lidar.period()).inverse() * pose_at_abs(t_end),
                                 lidar.period());
    if (truth_dewarp != TruthDewarp::kNone) scans.back().time.clear();
    gt.push_back(pose_at_abs(t_end));
  }
  const Pose3 g0inv = gt.front().inverse();
  for (auto& p : gt) p = g0inv * p;
}

void sectionSpeed(const odometry::LoamParams& params, const std::vector<double>& kitti_times) {
  std::cout << "\n== (b) speed per scan, one thread: CPU time of the thread (wall clock in brackets) ==\n";
  std::cout << std::fixed << std::setprecision(1);
  if (!kitti_times.empty())
    std::cout << "  KITTI HDL-64E (~120k points, 64 lines x ~1900): median " << bench::quantile(kitti_times, 0.5)
              << " ms, p95 " << bench::quantile(kitti_times, 0.95) << " ms  (" << kitti_times.size()
              << " scans; wall median " << bench::quantile(g_wall_ms, 0.5) << " ms)\n";
  for (int rings : {64, 128}) {
    sim::LidarModel lidar = test_support::idealLidar();
    lidar.beams = rings;
    lidar.columns = 1024;
    if (rings == 128) lidar.fov_up_deg = 22.5, lidar.fov_down_deg = -22.5;
    lidar.range_sigma = 0.01;
    std::vector<Scan> scans;
    std::vector<Pose3> gt;
    syntheticTrial(lidar, 10.0, 1.0, 30, 7, scans, gt, false);
    std::vector<double> times;
    g_wall_ms.clear();
    const auto est = runOdometry(scans, params, &times);
    std::size_t pts = 0;
    for (const auto& s : scans) pts += s.size();
    const auto seg = odometry::segmentErrors(est, gt, {10.0}, 1);
    std::cout << "  synthetic " << rings << " x 1024 (" << pts / scans.size() << " returns/scan): median "
              << bench::quantile(times, 0.5) << " ms, p95 " << bench::quantile(times, 0.95) << " ms (wall median "
              << bench::quantile(g_wall_ms, 0.5) << " ms)  (drift over 10 m: " << std::setprecision(2)
              << seg[0].translation_percent << " %, " << std::setprecision(4) << seg[0].rotation_deg_per_m
              << " deg/m)\n"
              << std::setprecision(1);
    // Per-stage split (CPU ms per scan, median): scan lines + features, local-map update (3-scan union + k-d
    // trees), the rest (guess scoring, registration, deskew) = total - the two.
    std::vector<double> t_feat, t_map;
    odometry::LocalFeatureMap map(static_cast<std::size_t>(std::max(1, params.num_local_map_scans)),
                                  params.map_edge_voxel_size, params.map_planar_voxel_size);
    for (const Scan& s : scans) {
      double c0 = threadCpuMs();
      odometry::LoamFeatures f = extractFeatures(organizeScanLines(s, params), params);
      thinPlanarFeatures(f, params.planar_feature_voxel_size);
      t_feat.push_back(threadCpuMs() - c0);
      c0 = threadCpuMs();
      map.add(f.edge_points, f.planar_points);
      t_map.push_back(threadCpuMs() - c0);
    }
    const double feat = bench::quantile(t_feat, 0.5), mapu = bench::quantile(t_map, 0.5);
    std::cout << "    split: scan lines + features " << feat << " ms, local-map update " << mapu
              << " ms, registration (guesses, k-NN, fits, Gauss-Newton, deskew) ~"
              << bench::quantile(times, 0.5) - feat - mapu << " ms\n";
  }
}

void sectionDrift(const odometry::LoamParams& params) {
  std::cout << "\n== (c) drift on synthetic trials with motion distortion (targets <= 1.0 %, <= 0.01 deg/m) ==\n";
  std::cout << "  built-in ray-cast street (OS1-64-like 64 x 1024, 10 Hz, 1 cm range noise, per-point times)\n";
  struct Trial {
    const char* name;
    double speed;
    int scans;
    bool walking;
  };
  for (const Trial& tr : {Trial{"walking 1.4 m/s", 1.4, 800, true}, Trial{"driving 10 m/s", 10.0, 150, false}}) {
    sim::LidarModel lidar = test_support::idealLidar();
    lidar.range_sigma = 0.01;
    std::vector<Scan> scans;
    std::vector<Pose3> gt;
    syntheticTrial(lidar, tr.speed, 1.0, tr.scans, 11, scans, gt, tr.walking);
    std::vector<odometry::OdometryResult> res;
    const auto est = runOdometry(scans, params, nullptr, &res);
    std::size_t warn = 0;
    for (const auto& r : res) warn += r.ok ? 0 : 1;
    double len = 0.0;
    for (std::size_t i = 1; i < gt.size(); ++i) len += (gt[i].translation() - gt[i - 1].translation()).norm();
    std::cout << "  " << tr.name << ", " << std::fixed << std::setprecision(0) << len << " m, " << scans.size()
              << " scans, " << warn << " warnings, ATE " << std::setprecision(3)
              << odometry::absoluteTrajectoryError(est, gt).rmse << " m\n";
    for (const auto& e : odometry::segmentErrors(est, gt, {25.0, 50.0, 100.0}, 1)) {
      std::cout << "    " << std::setw(4) << std::setprecision(0) << e.length << " m: ";
      if (e.count == 0)
        std::cout << "n/a\n";
      else
        std::cout << std::setprecision(3) << e.translation_percent << " %  " << std::setprecision(5)
                  << e.rotation_deg_per_m << " deg/m  (" << e.count << " segments)  "
                  << ((e.translation_percent <= 1.0 && e.rotation_deg_per_m <= 0.01) ? "ok" : "MISS") << "\n";
    }
  }
}

/// Where the walk's rotation drift comes from: the same street walk with its sway; with the sweeps dewarped by the
/// true motion (a perfect deskew); dewarped at constant velocity with the true start and end poses (the odometry's
/// deskew model without its estimation error); and without the sway (a sensor at a constant height, as on a ground
/// robot), with its point times and dewarped with the true motion. Per variant the 25 m drift and the mean and
/// spread of the per-scan rotation error about the sensor's roll / pitch / yaw axes (the mean, times the scans
/// per metre, is the part of the drift that is a bias).
void sectionDriftSources(const odometry::LoamParams& params) {
  std::cout << "\n== (d) sources of the walk's rotation drift (street, 1.4 m/s, 800 scans, 1 cm range noise) ==\n";
  struct Variant {
    const char* name;
    bool sway;
    TruthDewarp truth_dewarp;
  };
  for (const Variant& v :
       {Variant{"walking with sway (as in c)", true, TruthDewarp::kNone},
        Variant{"same, dewarped with the true motion", true, TruthDewarp::kTrueMotion},
        Variant{"same, true sweep motion at constant velocity", true, TruthDewarp::kTrueConstantVelocity},
        Variant{"walking without sway", false, TruthDewarp::kNone},
        Variant{"without sway, dewarped with the true motion", false, TruthDewarp::kTrueMotion}}) {
    sim::LidarModel lidar = test_support::idealLidar();
    lidar.range_sigma = 0.01;
    std::vector<Scan> scans;
    std::vector<Pose3> gt;
    syntheticTrial(lidar, 1.4, 1.0, 800, 11, scans, gt, v.sway, v.truth_dewarp);
    const auto est = runOdometry(scans, params, nullptr);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum2 = Eigen::Vector3d::Zero();
    for (std::size_t k = 1; k < est.size(); ++k) {
      const Pose3 e = (gt[k - 1].inverse() * gt[k]).inverse() * (est[k - 1].inverse() * est[k]);
      const Eigen::Vector3d w = logSO3(e.linear()) * kRadToDeg;
      sum += w;
      sum2 += w.cwiseProduct(w);
    }
    const double n = static_cast<double>(est.size() - 1);
    const Eigen::Vector3d mean = sum / n;
    const Eigen::Vector3d sd = (sum2 / n - mean.cwiseProduct(mean)).cwiseMax(0.0).cwiseSqrt();
    const auto seg = odometry::segmentErrors(est, gt, {25.0}, 1);
    std::cout << "  " << std::left << std::setw(46) << v.name << std::right << std::fixed << std::setprecision(5)
              << "25 m: " << seg[0].rotation_deg_per_m << " deg/m;  per scan (deg) roll/pitch/yaw mean " << mean.x()
              << " " << mean.y() << " " << mean.z() << ", sd " << std::setprecision(4) << sd.x() << " " << sd.y() << " "
              << sd.z() << "\n";
  }
}
}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  std::string config, only = "abcd";
  int repeat = 5;
  cosmo::CommandLine app("bench_odometry",
                         "LOAM odometry: (a) accuracy on real scan snippets, (b) speed per scan, (c, d) drift on "
                         "synthetic trials.");
  cosmo::addModuleConfig(app, config, "odometry");
  app.add_option("--repeat", repeat, "runs per timed scan")->capture_default_str();
  app.add_option("--only", only, "the sections to run")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  try {
    odometry::LoamParams params;
    if (!config.empty()) params = odometry::LoamParams::fromConfig(cosmo::ConfigNode::load(config));
    std::vector<double> kitti_times;
    if (only.find('a') != std::string::npos) sectionReal(params, kitti_times, repeat);
    if (only.find('b') != std::string::npos) sectionSpeed(params, kitti_times);
    if (only.find('c') != std::string::npos) sectionDrift(params);
    if (only.find('d') != std::string::npos) sectionDriftSources(params);
  } catch (const std::exception& e) {
    std::cerr << "bench_odometry: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
