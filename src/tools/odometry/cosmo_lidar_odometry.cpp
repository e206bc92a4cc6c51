// cosmo_lidar_odometry (the library target is already named cosmo_odometry): LOAM odometry over a folder of scans (PCD, KITTI .bin) or a bag topic; writes the trajectory
// (KITTI / TUM) and, given reference poses, prints ATE (SE(3)-aligned), KITTI-style segment errors and the
// time per scan.
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
  std::cerr << "usage: cosmo_lidar_odometry --scans DIR [--poses KITTI_POSES [--calib CALIB.txt]]\n"
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
  } catch (...) {
    return -1;
  }
}
}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  std::map<std::string, std::string> a;
  bool quiet = false;
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
  try {
    LoamParams params;
    if (a.count("config")) params = LoamParams::fromConfig(ConfigNode::load(a["config"]));
    const double period = a.count("period") ? std::stod(a["period"]) : 0.1;
    const long first = a.count("first") ? std::stol(a["first"]) : 0;
    const long count = a.count("count") ? std::stol(a["count"]) : -1;

    std::vector<Pose3> kitti_ref;
    if (a.count("poses")) {
      kitti_ref = readKittiPoses(a["poses"]);
      if (a.count("calib")) kitti_ref = kittiPosesToLidar(kitti_ref, readKittiCalibTr(a["calib"]));
    }
    std::vector<double> segments{10.0, 20.0, 40.0, 100.0};
    if (a.count("segments")) {
      segments.clear();
      std::stringstream ss(a["segments"]);
      std::string item;
      while (std::getline(ss, item, ',')) segments.push_back(std::stod(item));
    }
    Pose3 extrinsic = Pose3::Identity();
    if (a.count("extrinsic")) {
      std::stringstream ss(a["extrinsic"]);
      std::vector<double> v;
      double x;
      while (ss >> x) v.push_back(x);
      extrinsic = parsePoseNumbers(v, "--extrinsic");
    }
    Trajectory stamped_ref;
    if (a.count("reference-tum")) stamped_ref = readTumTrajectory(a["reference-tum"]);
    if (a.count("reference-csv")) stamped_ref = readMcdPoseCsv(a["reference-csv"]);

    LoamOdometry odom(params);
    std::vector<Pose3> est, ref;
    Trajectory est_traj;
    std::vector<double> times_ms, cpu_ms;
    std::size_t warnings = 0;
    auto process = [&](Scan scan, long frame, const std::string& name) {
      bench::Stopwatch sw;
      const double cpu0 = threadCpuMs();
      const OdometryResult r = odom.update(scan);
      times_ms.push_back(sw.elapsedMs());
      cpu_ms.push_back(threadCpuMs() - cpu0);
      est.push_back(r.pose);
      if (scan.stamp > 0 && (est_traj.empty() || scan.stamp > est_traj.endStamp())) est_traj.append(scan.stamp, r.pose);
      if (!kitti_ref.empty()) {
        if (frame < 0 || static_cast<std::size_t>(frame) >= kitti_ref.size())
          throw std::runtime_error(name + ": no reference pose line for frame " + std::to_string(frame));
        ref.push_back(kitti_ref[frame]);
      } else if (!stamped_ref.empty()) {
        const auto p = stamped_ref.at(scan.stamp);
        if (p) ref.push_back(*p * extrinsic);
      }
      if (!r.ok) {
        ++warnings;
        std::cerr << "warning: " << name << ": " << r.warning << "\n";
      }
      if (!quiet)
        std::cout << std::fixed << std::setprecision(3) << name << "  t=" << r.pose.translation().transpose()
                  << "  step=" << r.delta.translation().norm() << " m  feats " << r.num_edge_features << "/"
                  << r.num_planar_features << "  it " << r.iterations << "  inl " << r.inlier_fraction << "  "
                  << r.initial_guess << "  " << times_ms.back() << " ms\n";
    };

    if (a.count("scans")) {
      const auto files = listScanFiles(a["scans"]);
      if (files.empty()) throw std::runtime_error(a["scans"] + ": no .pcd / .bin scan files");
      long n = 0;
      for (std::size_t i = 0; i < files.size(); ++i) {
        if (static_cast<long>(i) < first) continue;
        if (count >= 0 && n >= count) break;
        ++n;
        Scan s = readScanFile(files[i]);
        const long frame = frameIndexOf(files[i]);
        s.stamp = toStampNs(1.0 + static_cast<double>(frame >= 0 ? frame : static_cast<long>(i)) * period);
        process(std::move(s), frame >= 0 ? frame : static_cast<long>(i), fs::path(files[i]).filename().string());
      }
    } else {
      ros_glue::ScanBagReader reader(a["bag"], a["topic"]);
      Scan s;
      long i = 0, n = 0;
      while (reader.next(s)) {
        if (i++ < first) continue;
        if (count >= 0 && n >= count) break;
        ++n;
        process(s, i - 1, a["topic"] + "#" + std::to_string(i - 1));
      }
    }

    if (a.count("out-kitti")) writeKittiPoses(a["out-kitti"], est);
    if (a.count("out-tum")) writeTumTrajectory(a["out-tum"], est_traj);

    std::cout << std::fixed << std::setprecision(3);
    std::cout << "scans: " << est.size() << "  warnings: " << warnings << "\n";
    std::cout << "time per scan: median " << bench::quantile(times_ms, 0.5) << " ms, p95 "
              << bench::quantile(times_ms, 0.95) << " ms wall; CPU time median " << bench::quantile(cpu_ms, 0.5)
              << " ms, p95 " << bench::quantile(cpu_ms, 0.95) << " ms (one thread)\n";
    if (!ref.empty() && ref.size() == est.size()) {
      // Express the reference relative to its first pose, like the odometry.
      const Pose3 r0inv = ref.front().inverse();
      for (auto& p : ref) p = r0inv * p;
      const AteResult ate = absoluteTrajectoryError(est, ref);
      std::cout << "ATE (SE(3)-aligned): rmse " << ate.rmse << " m, mean " << ate.mean << " m, max " << ate.max
                << " m\n";
      double path = 0.0;
      for (std::size_t i = 1; i < ref.size(); ++i) path += (ref[i].translation() - ref[i - 1].translation()).norm();
      std::cout << "reference path length " << path << " m\n";
      for (const auto& e : segmentErrors(est, ref, segments)) {
        std::cout << "segment " << std::setw(5) << e.length << " m: ";
        if (e.count == 0)
          std::cout << "n/a (trajectory too short)\n";
        else
          std::cout << std::setprecision(3) << e.translation_percent << " %  " << std::setprecision(5)
                    << e.rotation_deg_per_m << " deg/m  (" << e.count << " segments)\n" << std::setprecision(3);
      }
      if (est.size() >= 2) {
        double worst_t = 0, worst_r = 0;
        for (std::size_t i = 1; i < est.size(); ++i) {
          const Pose3 de = est[i - 1].inverse() * est[i], dg = ref[i - 1].inverse() * ref[i];
          worst_t = std::max(worst_t, translationError(de, dg));
          worst_r = std::max(worst_r, rotationErrorRad(de, dg) * 180.0 / M_PI);
        }
        std::cout << "worst per-step error: " << worst_t * 100.0 << " cm, " << worst_r << " deg\n";
      }
      const auto fills = findConstantMotionRuns(ref);
      if (!fills.empty()) {
        std::cout << "reference moves at a perfectly constant velocity (steps equal within 2 mm / 0.005 deg for >= 10 "
                     "steps) over scans";
        for (const auto& f : fills) std::cout << " " << f.first << "-" << f.last;
        std::cout << ": expected of a simulated reference; in a measured one (GPS/INS) these are gaps filled by "
                     "interpolation, and per-step errors there measure the fill\n";
      }
    } else if (!ref.empty()) {
      std::cout << "reference covers " << ref.size() << " of " << est.size() << " scans: no evaluation\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "cosmo_lidar_odometry: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
