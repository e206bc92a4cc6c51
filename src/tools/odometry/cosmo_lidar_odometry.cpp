// cosmo_lidar_odometry (the library target is already named cosmo_odometry): LOAM odometry over a folder of scans (PCD,
// KITTI .bin) or a bag topic; writes the trajectory (KITTI / TUM) and, given reference poses, prints ATE
// (SE(3)-aligned), KITTI-style segment errors and the time per scan.
//
//   cosmo_lidar_odometry --scans DIR [--poses KITTI_POSES [--calib CALIB.txt]] [--out-kitti F] [--out-tum F]
//                  [--config config/odometry.yaml] [--period 0.1] [--first N] [--count M] [--quiet]
//   cosmo_lidar_odometry --bag FILE --topic T [--reference-tum F | --reference-csv pose_inW.csv]
//                        [--extrinsic "x y z qx qy qz qw"] [...]
//   --segments 10,20,40,100 (default) sets the segment lengths (m) of the relative errors.
#include "cosmo/trials/trial_scans.hpp"

#include <ctime>
#include <filesystem>
#include <optional>
#include <sstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/odometry/trajectory_metrics.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {
/// CPU time of this thread (ms): less sensitive to other processes than the wall clock.
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

/// Frame index from a file name like 000094.bin or a folder 000003/points.bin; -1 if none.
long frameIndexOf(const std::string& path) {
  fs::path p(path);
  std::string stem = p.stem().string();
  if (stem == "points" || stem == "cloud") stem = p.parent_path().filename().string();
  try {
    std::size_t used = 0;
    const long v = std::stol(stem, &used);
    return used == stem.size() ? v : -1;
  } catch (...) { return -1; }
}
struct Options {
  std::string scans, poses, calib, bag, topic, reference_tum, reference_csv, out_kitti, out_tum, config;
  std::vector<double> extrinsic;                          ///< x y z qx qy qz qw
  std::vector<double> segments{10.0, 20.0, 40.0, 100.0};  ///< segment lengths of the relative errors, m
  double period = 0.1;
  long first = 0, count = -1;
  bool quiet = false;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  cosmo::CommandLine app("cosmo_lidar_odometry",
                         "LOAM odometry over a folder of scans (PCD, KITTI .bin) or a bag topic; writes the "
                         "trajectory (KITTI / TUM) and, given reference poses, prints ATE (SE(3)-aligned), "
                         "KITTI-style segment errors and the time per scan.");
  CLI::Option* scans = app.add_option("--scans", o.scans,
                                      "a folder of scans, matched to KITTI pose lines by the number in their file "
                                      "name (000094.bin -> line 94) and stamped index * --period")
                           ->type_name("DIR");
  app.add_option("--poses", o.poses, "KITTI poses of the scans")->type_name("KITTI_POSES");
  app.add_option("--calib", o.calib, "KITTI calibration (the poses are moved to the LiDAR)")->type_name("CALIB.txt");
  CLI::Option* bag = app.add_option("--bag", o.bag, "a bag instead of a folder")->excludes(scans);
  app.add_option("--topic", o.topic, "the bag's point-cloud topic")->needs(bag);
  app.add_option("--reference-tum", o.reference_tum, "a stamped reference trajectory (TUM)")->type_name("F");
  app.add_option("--reference-csv", o.reference_csv, "a stamped reference trajectory (MCD pose_inW.csv)")
      ->type_name("F");
  app.add_option("--extrinsic", o.extrinsic,
                 "T_body_lidar, when the stamped reference is a body trajectory (LiDAR = body * extrinsic)")
      ->type_name("\"x y z qx qy qz qw\"")
      ->delimiter(' ');
  app.add_option("--out-kitti", o.out_kitti, "write the estimated poses (KITTI)")->type_name("F");
  app.add_option("--out-tum", o.out_tum, "write the estimated trajectory (TUM)")->type_name("F");
  cosmo::addModuleConfig(app, o.config, "odometry");
  app.add_option("--period", o.period, "seconds between folder scans")->capture_default_str();
  app.add_option("--first", o.first, "the first scan")->capture_default_str();
  app.add_option("--count", o.count, "at most this many scans (-1: all)")->capture_default_str();
  app.add_option("--segments", o.segments, "segment lengths of the relative errors, m")
      ->delimiter(',')
      ->capture_default_str();
  app.add_flag("--quiet", o.quiet, "no line per scan");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return exit_code;
  if (o.scans.empty() && (o.bag.empty() || o.topic.empty())) {
    std::cerr << "cosmo_lidar_odometry: give --scans DIR, or --bag FILE and --topic TOPIC\n";
    return 2;
  }
  return std::nullopt;
}

/// The reference poses given: KITTI pose lines (one per frame), or a stamped trajectory of the body moved to the
/// LiDAR by the extrinsic.
struct Reference {
  std::vector<Pose3> kitti;
  Trajectory stamped;
  Pose3 extrinsic = Pose3::Identity();

  /// The reference pose of a scan; throws for a KITTI frame without a pose line.
  std::optional<Pose3> of(const Scan& scan, long frame, const std::string& name) const {
    if (!kitti.empty()) {
      if (frame < 0 || static_cast<std::size_t>(frame) >= kitti.size())
        throw std::runtime_error(name + ": no reference pose line for frame " + std::to_string(frame));
      return kitti[frame];
    }
    if (stamped.empty()) return std::nullopt;
    const auto p = stamped.at(scan.stamp);
    if (!p) return std::nullopt;
    return *p * extrinsic;
  }
};

Reference readReference(const Options& o) {
  Reference ref;
  if (!o.poses.empty()) {
    ref.kitti = cosmo::readKittiPoses(o.poses);
    if (!o.calib.empty()) ref.kitti = cosmo::kittiPosesToLidar(ref.kitti, cosmo::readKittiCalibTr(o.calib));
  }
  if (!o.extrinsic.empty()) ref.extrinsic = cosmo::parsePoseNumbers(o.extrinsic, "--extrinsic");
  if (!o.reference_tum.empty()) ref.stamped = cosmo::readTumTrajectory(o.reference_tum);
  if (!o.reference_csv.empty()) ref.stamped = cosmo::readMcdPoseCsv(o.reference_csv);
  return ref;
}

/// LOAM over the scans one by one: the estimated poses, the reference poses of the scans that have one, the
/// time per scan.
class OdometryRun {
 public:
  OdometryRun(const odometry::LoamParams& params, Reference reference, bool quiet)
      : odom_(params), reference_(std::move(reference)), quiet_(quiet) {}

  void process(const Scan& scan, long frame, const std::string& name) {
    bench::Stopwatch sw;
    const double cpu0 = threadCpuMs();
    const odometry::OdometryResult r = odom_.update(scan);
    times_ms.push_back(sw.elapsedMs());
    cpu_ms.push_back(threadCpuMs() - cpu0);
    est.push_back(r.pose);
    if (scan.stamp > 0 && (est_traj.empty() || scan.stamp > est_traj.endStamp())) est_traj.append(scan.stamp, r.pose);
    if (const std::optional<Pose3> p = reference_.of(scan, frame, name)) ref.push_back(*p);
    if (!r.ok) {
      ++warnings;
      std::cerr << "warning: " << name << ": " << r.warning << "\n";
    }
    if (!quiet_)
      std::cout << std::fixed << std::setprecision(3) << name << "  t=" << r.pose.translation().transpose()
                << "  step=" << r.delta.translation().norm() << " m  feats " << r.num_edge_features << "/"
                << r.num_planar_features << "  it " << r.iterations << "  inl " << r.inlier_fraction << "  "
                << r.initial_guess << "  " << times_ms.back() << " ms\n";
  }

  std::vector<Pose3> est, ref;
  Trajectory est_traj;
  std::vector<double> times_ms, cpu_ms;
  std::size_t warnings = 0;

 private:
  odometry::LoamOdometry odom_;
  Reference reference_;
  bool quiet_;
};

/// The scans from --first, at most --count of them.
struct Range {
  long first = 0, count = -1;
};

/// A folder of scan files, stamped by their frame number times the period.
void runFolder(const std::string& dir, const Range& range, double period, OdometryRun& run) {
  const auto files = listScanFiles(dir);
  if (files.empty()) throw std::runtime_error(dir + ": no .pcd / .bin scan files");
  long n = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (static_cast<long>(i) < range.first) continue;
    if (range.count >= 0 && n >= range.count) break;
    ++n;
    Scan s = readScanFile(files[i]);
    const long frame = frameIndexOf(files[i]);
    s.stamp = toStampNs(1.0 + static_cast<double>(frame >= 0 ? frame : static_cast<long>(i)) * period);
    run.process(s, frame >= 0 ? frame : static_cast<long>(i), fs::path(files[i]).filename().string());
  }
}

void runBag(const std::string& bag, const std::string& topic, const Range& range, OdometryRun& run) {
  trials::Ros1ScanSource reader(bag, topic);
  Scan s;
  long i = 0, n = 0;
  while (reader.next(s)) {
    if (i++ < range.first) continue;
    if (range.count >= 0 && n >= range.count) break;
    ++n;
    run.process(s, i - 1, topic + "#" + std::to_string(i - 1));
  }
}

void printTiming(const OdometryRun& run) {
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "scans: " << run.est.size() << "  warnings: " << run.warnings << "\n";
  std::cout << "time per scan: median " << bench::quantile(run.times_ms, 0.5) << " ms, p95 "
            << bench::quantile(run.times_ms, 0.95) << " ms wall; CPU time median " << bench::quantile(run.cpu_ms, 0.5)
            << " ms, p95 " << bench::quantile(run.cpu_ms, 0.95) << " ms (one thread)\n";
}

void printSegmentErrors(const std::vector<Pose3>& est, const std::vector<Pose3>& ref,
                        const std::vector<double>& segments) {
  for (const auto& e : odometry::segmentErrors(est, ref, segments)) {
    std::cout << "segment " << std::setw(5) << e.length << " m: ";
    if (e.count == 0)
      std::cout << "n/a (trajectory too short)\n";
    else
      std::cout << std::setprecision(3) << e.translation_percent << " %  " << std::setprecision(5)
                << e.rotation_deg_per_m << " deg/m  (" << e.count << " segments)\n"
                << std::setprecision(3);
  }
}

void printWorstStep(const std::vector<Pose3>& est, const std::vector<Pose3>& ref) {
  if (est.size() < 2) return;
  double worst_t = 0, worst_r = 0;
  for (std::size_t i = 1; i < est.size(); ++i) {
    const Pose3 de = est[i - 1].inverse() * est[i], dg = ref[i - 1].inverse() * ref[i];
    worst_t = std::max(worst_t, odometry::translationError(de, dg));
    worst_r = std::max(worst_r, odometry::rotationErrorRad(de, dg) * 180.0 / M_PI);
  }
  std::cout << "worst per-step error: " << worst_t * 100.0 << " cm, " << worst_r << " deg\n";
}

void printConstantMotionRuns(const std::vector<Pose3>& ref) {
  const auto fills = odometry::findConstantMotionRuns(ref);
  if (fills.empty()) return;
  std::cout << "reference moves at a perfectly constant velocity (steps equal within 2 mm / 0.005 deg for >= 10 "
               "steps) over scans";
  for (const auto& f : fills) std::cout << " " << f.first << "-" << f.last;
  std::cout << ": expected of a simulated reference; in a measured one (GPS/INS) these are gaps filled by "
               "interpolation, and per-step errors there measure the fill\n";
}

/// ATE, path length, segment errors, the worst step and the reference's constant-motion runs, when every scan
/// has a reference pose.
void printEvaluation(const std::vector<Pose3>& est, std::vector<Pose3> ref, const std::vector<double>& segments) {
  if (ref.empty()) return;
  if (ref.size() != est.size()) {
    std::cout << "reference covers " << ref.size() << " of " << est.size() << " scans: no evaluation\n";
    return;
  }
  // Express the reference relative to its first pose, like the odometry.
  const Pose3 r0inv = ref.front().inverse();
  for (auto& p : ref) p = r0inv * p;
  const odometry::AteResult ate = odometry::absoluteTrajectoryError(est, ref);
  std::cout << "ATE (SE(3)-aligned): rmse " << ate.rmse << " m, mean " << ate.mean << " m, max " << ate.max << " m\n";
  double path = 0.0;
  for (std::size_t i = 1; i < ref.size(); ++i) path += (ref[i].translation() - ref[i - 1].translation()).norm();
  std::cout << "reference path length " << path << " m\n";
  printSegmentErrors(est, ref, segments);
  printWorstStep(est, ref);
  printConstantMotionRuns(ref);
}

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  Options o;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
  try {
    odometry::LoamParams params;
    if (!o.config.empty()) params = odometry::LoamParams::fromConfig(cosmo::ConfigNode::load(o.config));
    const Range range{o.first, o.count};
    OdometryRun run(params, readReference(o), o.quiet);
    if (!o.scans.empty())
      runFolder(o.scans, range, o.period, run);
    else
      runBag(o.bag, o.topic, range, run);
    if (!o.out_kitti.empty()) cosmo::writeKittiPoses(o.out_kitti, run.est);
    if (!o.out_tum.empty()) cosmo::writeTumTrajectory(o.out_tum, run.est_traj);
    printTiming(run);
    printEvaluation(run.est, run.ref, o.segments);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_lidar_odometry: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
