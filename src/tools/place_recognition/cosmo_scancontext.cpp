// cosmo_scancontext: incremental ScanContext place recognition over a folder of scans with reference poses,
// precision / recall of the top candidate over a range of thresholds, and times.
//
//   cosmo_scancontext <scan_folder> <poses.txt> [--calib calib.txt] [--config place_recognition.yaml]
//                     [--exclude N] [--radius M] [--thresholds lo:hi:step] [--stride N] [--list]
//
// Scans: .pcd / KITTI .bin files sorted by name. Poses: KITTI format (12 numbers a line); scan file NNNNNN.*
// takes pose line NNNNNN when the name is a number, else the scan's position in the folder. With --calib the
// poses are KITTI camera poses, turned into LiDAR poses with the calib's Tr.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/place_recognition/revisit_evaluation.hpp"

namespace {

void usage() {
  std::cerr << "usage: cosmo_scancontext <scan_folder> <poses.txt> [--calib calib.txt] [--config file.yaml]\n"
               "         [--exclude N] [--radius M] [--thresholds lo:hi:step] [--stride N] [--list]\n"
               "  incremental search (each scan vs the earlier ones, the N most recent excluded), then precision\n"
               "  and recall of the top candidate (true when the reference positions are within M m, default 5)\n";
}

std::size_t poseIndexOf(const std::string& file, std::size_t position) {
  const std::string stem = std::filesystem::path(file).stem().string();
  if (!stem.empty() && stem.find_first_not_of("0123456789") == std::string::npos) return std::stoul(stem);
  const std::string parent = std::filesystem::path(file).parent_path().filename().string();  // NNNNNN/points.bin
  if (!parent.empty() && parent.find_first_not_of("0123456789") == std::string::npos) return std::stoul(parent);
  return position;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cosmo;
  std::vector<std::string> positional;
  std::string calib, config;
  int exclude = -1, stride = -1;
  double radius = 5.0, lo = 0.05, hi = 0.6, step = 0.05;
  bool list = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
        return argv[++i];
      };
      if (a == "--calib")
        calib = value();
      else if (a == "--config")
        config = value();
      else if (a == "--exclude")
        exclude = std::stoi(value());
      else if (a == "--radius")
        radius = std::stod(value());
      else if (a == "--stride")
        stride = std::stoi(value());
      else if (a == "--list")
        list = true;
      else if (a == "--thresholds") {
        const std::string v = value();
        if (std::sscanf(v.c_str(), "%lf:%lf:%lf", &lo, &hi, &step) != 3 || step <= 0.0 || hi < lo)
          throw std::runtime_error("--thresholds expects lo:hi:step, got '" + v + "'");
      } else if (a == "-h" || a == "--help") {
        usage();
        return 0;
      } else if (!a.empty() && a[0] == '-')
        throw std::runtime_error("unknown option " + a);
      else
        positional.push_back(a);
    }
    if (positional.size() != 2) {
      usage();
      return 2;
    }
    PlaceRecognitionParams params;
    if (!config.empty()) params = PlaceRecognitionParams::fromConfig(ConfigNode::load(config));
    if (exclude >= 0) params.exclude_recent = exclude;
    if (stride > 0) params.sc.point_stride = stride;

    std::vector<Pose3> poses = readKittiPoses(positional[1]);
    if (!calib.empty()) poses = kittiPosesToLidar(poses, readKittiCalibTr(calib));
    const std::vector<std::string> files = listScanFiles(positional[0]);
    if (files.empty()) throw std::runtime_error(positional[0] + ": no .pcd / .bin scans found");

    std::vector<ScanContext> descriptors;
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::size_t> pose_index;
    std::vector<double> descriptor_ms;
    std::size_t points = 0;
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::size_t k = poseIndexOf(files[i], i);
      if (k >= poses.size())
        throw std::runtime_error(files[i] + ": pose line " + std::to_string(k) + " is beyond " + positional[1] + " (" +
                                 std::to_string(poses.size()) + " poses)");
      const Scan scan = readScanFile(files[i]);
      points += scan.size();
      bench::Stopwatch sw;
      descriptors.push_back(makeScanContext(scan, params.sc));
      descriptor_ms.push_back(sw.elapsedMs());
      positions.push_back(poses[k].translation());
      pose_index.push_back(k);
    }

    // Incremental search, timed per query (search + insertion).
    std::vector<double> query_ms;
    std::vector<QueryOutcome> outcomes;
    {
      ScanContextDatabase db(params.databaseParams());
      const auto excluded = static_cast<std::size_t>(params.exclude_recent);
      for (std::size_t i = 0; i < descriptors.size(); ++i) {
        bench::Stopwatch sw;
        const std::size_t searchable = i > excluded ? i - excluded : 0;
        const auto matches = db.query(descriptors[i], searchable);
        db.insert(i, descriptors[i]);
        query_ms.push_back(sw.elapsedMs());
        QueryOutcome o;
        for (std::size_t j = 0; j < searchable; ++j) {
          const double d = (positions[j] - positions[i]).norm();
          if (o.nearest_separation < 0.0 || d < o.nearest_separation) o.nearest_separation = d;
        }
        if (!matches.empty()) {
          o.has_candidate = true;
          o.match = matches.front().id;
          o.distance = matches.front().match.distance;
          o.yaw = matches.front().match.yaw;
          o.match_separation = (positions[o.match] - positions[i]).norm();
        }
        outcomes.push_back(o);
        if (list) {
          if (o.has_candidate)
            std::printf("scan %zu: top %zu distance %.4f yaw %.1f deg  separation %.2f m (nearest %.2f m)\n",
                        pose_index[i], pose_index[o.match], o.distance, o.yaw * 180.0 / M_PI, o.match_separation,
                        o.nearest_separation);
          else
            std::printf("scan %zu: no candidate\n", pose_index[i]);
        }
      }
    }

    std::printf("%zu scans (%.0f points on average) from %s, exclude_recent %d, revisit radius %.1f m\n", files.size(),
                static_cast<double>(points) / files.size(), positional[0].c_str(), params.exclude_recent, radius);
    std::printf("threshold  detections  true_pos  revisits  precision  recall\n");
    for (double t = lo; t <= hi + 1e-9; t += step) {
      const PrPoint p = precisionRecallAt(outcomes, t, radius);
      std::printf("%9.3f  %10zu  %8zu  %8zu  %9.3f  %6.3f%s\n", t, p.detections, p.true_positives, p.revisits,
                  p.precision, p.recall, std::abs(t - params.threshold) < 1e-9 ? "   <- default" : "");
    }
    const PrPoint d = precisionRecallAt(outcomes, params.threshold, radius);
    std::printf("default threshold %.3f: precision %.3f recall %.3f (%zu/%zu detections correct, %zu revisits)\n",
                params.threshold, d.precision, d.recall, d.true_positives, d.detections, d.revisits);
    std::printf("descriptor time: median %.3f ms, p95 %.3f ms (point_stride %d)\n", bench::quantile(descriptor_ms, 0.5),
                bench::quantile(descriptor_ms, 0.95), params.sc.point_stride);
    std::printf("query+insert time: median %.3f ms, p95 %.3f ms, max %.3f ms (database of up to %zu entries)\n",
                bench::quantile(query_ms, 0.5), bench::quantile(query_ms, 0.95), bench::quantile(query_ms, 1.0),
                descriptors.size());
  } catch (const std::exception& e) {
    std::cerr << "cosmo_scancontext: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
