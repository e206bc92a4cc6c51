// cosmo_lidar_odometry (the library target is already named cosmo_odometry): LOAM odometry over a folder of scans (PCD,
// KITTI .bin) or a bag topic; writes the trajectory (KITTI / TUM) and, given reference poses, prints ATE
// (SE(3)-aligned), KITTI-style segment errors and the time per scan.
//
//   cosmo_lidar_odometry --scans DIR [--poses KITTI_POSES [--calib CALIB.txt]] [--out-kitti F] [--out-tum F]
//                  [--config config/odometry.yaml] [--period 0.1] [--first N] [--count M] [--quiet]
//   cosmo_lidar_odometry --bag FILE --topic T [--reference-tum F | --reference-csv pose_inW.csv]
//                        [--extrinsic "x y z qx qy qz qw"] [...]
//   --segments 10,20,40,100 (default) sets the segment lengths (m) of the relative errors.
#include <cosmo/ros/bag_io.hpp>

#include <ctime>
#include <filesystem>
#include <sstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/bench/stopwatch.hpp"
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

void usage() {
  std::cerr
      << "usage: cosmo_lidar_odometry --scans DIR [--poses KITTI_POSES [--calib CALIB.txt]]\n"
         "                            | --bag FILE --topic TOPIC [--reference-tum F | --reference-csv pose_inW.csv]\n"
         "       [--out-kitti F] [--out-tum F] [--config config/odometry.yaml] [--period S]\n"
         "       [--first N] [--count M] [--segments 10,20,40,100] [--extrinsic \"x y z qx qy qz qw\"] [--quiet]\n"
         "--extrinsic: T_body_lidar, when the stamped reference is a body trajectory (LiDAR = body * extrinsic).\n"
         "Folder scans are matched to KITTI pose lines by the number in their file name (000094.bin ->\n"
         "line 94) and stamped index * period (default 0.1 s).\n";
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
using Args = std::map<std::string, std::string>;

/// The command line as --key value pairs; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Args& a, bool& quiet) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (k == "--quiet") {
      quiet = true;
    } else if (k == "-h" || k == "--help") {
      usage();
      return 0;
    } else if (k.rfind("--", 0) == 0 && i + 1 < argc) {
      a[k.substr(2)] = argv[++i];
    } else {
      std::cerr << "unknown or incomplete argument: " << k << "\n";
      usage();
      return 2;
    }
  }
  if (!a.count("scans") && !(a.count("bag") && a.count("topic"))) {
    usage();
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

Reference readReference(Args& a) {
  Reference ref;
  if (a.count("poses")) {
    ref.kitti = readKittiPoses(a["poses"]);
    if (a.count("calib")) ref.kitti = kittiPosesToLidar(ref.kitti, readKittiCalibTr(a["calib"]));
  }
  if (a.count("extrinsic")) {
    std::stringstream ss(a["extrinsic"]);
    std::vector<double> v;
    double x;
    while (ss >> x) v.push_back(x);
    ref.extrinsic = parsePoseNumbers(v, "--extrinsic");
  }
  if (a.count("reference-tum")) ref.stamped = readTumTrajectory(a["reference-tum"]);
  if (a.count("reference-csv")) ref.stamped = readMcdPoseCsv(a["reference-csv"]);
  return ref;
}

std::vector<double> segmentLengths(Args& a) {
  if (!a.count("segments")) return {10.0, 20.0, 40.0, 100.0};
  std::vector<double> segments;
  std::stringstream ss(a["segments"]);
  std::string item;
  while (std::getline(ss, item, ',')) segments.push_back(std::stod(item));
  return segments;
}

/// LOAM over the scans one by one: the estimated poses, the reference poses of the scans that have one, the
/// time per scan.
class OdometryRun {
 public:
  OdometryRun(const LoamParams& params, Reference reference, bool quiet)
      : odom_(params), reference_(std::move(reference)), quiet_(quiet) {}

  void process(const Scan& scan, long frame, const std::string& name) {
    bench::Stopwatch sw;
    const double cpu0 = threadCpuMs();
    const OdometryResult r = odom_.update(scan);
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
  LoamOdometry odom_;
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
  ros_glue::ScanBagReader reader(bag, topic);
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
  for (const auto& e : segmentErrors(est, ref, segments)) {
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
    worst_t = std::max(worst_t, translationError(de, dg));
    worst_r = std::max(worst_r, rotationErrorRad(de, dg) * 180.0 / M_PI);
  }
  std::cout << "worst per-step error: " << worst_t * 100.0 << " cm, " << worst_r << " deg\n";
}

void printConstantMotionRuns(const std::vector<Pose3>& ref) {
  const auto fills = findConstantMotionRuns(ref);
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
  const AteResult ate = absoluteTrajectoryError(est, ref);
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
  Args a;
  bool quiet = false;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, a, quiet)) return *exit_code;
  try {
    LoamParams params;
    if (a.count("config")) params = LoamParams::fromConfig(ConfigNode::load(a["config"]));
    const double period = a.count("period") ? std::stod(a["period"]) : 0.1;
    const Range range{a.count("first") ? std::stol(a["first"]) : 0, a.count("count") ? std::stol(a["count"]) : -1};
    const std::vector<double> segments = segmentLengths(a);
    OdometryRun run(params, readReference(a), quiet);
    if (a.count("scans"))
      runFolder(a["scans"], range, period, run);
    else
      runBag(a["bag"], a["topic"], range, run);
    if (a.count("out-kitti")) writeKittiPoses(a["out-kitti"], run.est);
    if (a.count("out-tum")) writeTumTrajectory(a["out-tum"], run.est_traj);
    printTiming(run);
    printEvaluation(run.est, run.ref, segments);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_lidar_odometry: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
