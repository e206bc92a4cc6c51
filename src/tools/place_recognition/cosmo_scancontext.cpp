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
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/place_recognition/revisit_evaluation.hpp"

namespace {

std::size_t poseIndexOf(const std::string& file, std::size_t position) {
  const std::string stem = std::filesystem::path(file).stem().string();
  if (!stem.empty() && stem.find_first_not_of("0123456789") == std::string::npos) return std::stoul(stem);
  const std::string parent = std::filesystem::path(file).parent_path().filename().string();  // NNNNNN/points.bin
  if (!parent.empty() && parent.find_first_not_of("0123456789") == std::string::npos) return std::stoul(parent);
  return position;
}

struct Options {
  std::vector<std::string> positional;  ///< scan folder, poses file
  std::string calib, config;
  int exclude = -1, stride = -1;
  double radius = 5.0, lo = 0.05, hi = 0.6, step = 0.05;
  bool list = false;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  cosmo::CommandLine app("cosmo_scancontext",
                         "Incremental ScanContext search (each scan vs the earlier ones, the N most recent "
                         "excluded), then precision and recall of the top candidate (true when the "
                         "reference positions are within --radius m).");
  o.positional.resize(2);
  app.add_option("SCAN_FOLDER", o.positional[0], ".pcd / KITTI .bin scans, sorted by name")->required();
  app.add_option("POSES", o.positional[1],
                 "KITTI poses (12 numbers a line): a scan NNNNNN.* takes pose line NNNNNN, else its position in the "
                 "folder")
      ->required();
  app.add_option("--calib", o.calib, "the poses are KITTI camera poses, turned into LiDAR poses with the calib's Tr")
      ->type_name("calib.txt");
  cosmo::addModuleConfig(app, o.config, "place recognition");
  app.add_option("--exclude", o.exclude, "the N most recent scans excluded (default: the config's exclude_recent)")
      ->type_name("N");
  app.add_option("--radius", o.radius, "revisit radius, m")->capture_default_str();
  app.add_option_function<std::string>(
         "--thresholds",
         [&o](const std::string& v) {
           if (std::sscanf(v.c_str(), "%lf:%lf:%lf", &o.lo, &o.hi, &o.step) != 3 || o.step <= 0.0 || o.hi < o.lo)
             throw CLI::ValidationError("--thresholds", "expects lo:hi:step, got '" + v + "'");
         },
         "distance thresholds of the precision-recall table")
      ->type_name("lo:hi:step")
      ->default_str("0.05:0.6:0.05");
  app.add_option("--stride", o.stride, "point stride of the descriptor (default: the config's point_stride)")
      ->type_name("N");
  app.add_flag("--list", o.list, "print every query's top candidate");
  return app.parseOrExit(argc, argv);
}

cosmo::place_recognition::PlaceRecognitionParams placeParams(const Options& o) {
  cosmo::place_recognition::PlaceRecognitionParams params;
  if (!o.config.empty())
    params = cosmo::place_recognition::PlaceRecognitionParams::fromConfig(cosmo::ConfigNode::load(o.config));
  if (o.exclude >= 0) params.exclude_recent = o.exclude;
  if (o.stride > 0) params.sc.point_stride = o.stride;
  return params;
}

/// Every scan's descriptor (timed) and reference position.
struct Described {
  std::vector<cosmo::place_recognition::ScanContext> descriptors;
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::size_t> pose_index;
  std::vector<double> descriptor_ms;
  std::size_t points = 0;
};

Described describeScans(const Options& o, const cosmo::place_recognition::PlaceRecognitionParams& params) {
  using namespace cosmo;
  using namespace cosmo::place_recognition;
  std::vector<Pose3> poses = readKittiPoses(o.positional[1]);
  if (!o.calib.empty()) poses = kittiPosesToLidar(poses, readKittiCalibTr(o.calib));
  const std::vector<std::string> files = listScanFiles(o.positional[0]);
  if (files.empty()) throw std::runtime_error(o.positional[0] + ": no .pcd / .bin scans found");
  Described d;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::size_t k = poseIndexOf(files[i], i);
    if (k >= poses.size())
      throw std::runtime_error(files[i] + ": pose line " + std::to_string(k) + " is beyond " + o.positional[1] + " (" +
                               std::to_string(poses.size()) + " poses)");
    const Scan scan = readScanFile(files[i]);
    d.points += scan.size();
    bench::Stopwatch sw;
    d.descriptors.push_back(makeScanContext(scan, params.sc));
    d.descriptor_ms.push_back(sw.elapsedMs());
    d.positions.push_back(poses[k].translation());
    d.pose_index.push_back(k);
  }
  return d;
}

void printOutcome(const Described& d, std::size_t i, const cosmo::place_recognition::QueryOutcome& o) {
  if (o.has_candidate)
    std::printf("scan %zu: top %zu distance %.4f yaw %.1f deg  separation %.2f m (nearest %.2f m)\n", d.pose_index[i],
                d.pose_index[o.match], o.distance, o.yaw * 180.0 / M_PI, o.match_separation, o.nearest_separation);
  else
    std::printf("scan %zu: no candidate\n", d.pose_index[i]);
}

/// Incremental search (each scan against the earlier ones, the most recent excluded), timed per query (search +
/// insertion): the top candidate of each.
std::vector<cosmo::place_recognition::QueryOutcome> searchIncrementally(
    const Described& d, const cosmo::place_recognition::PlaceRecognitionParams& params, bool list,
    std::vector<double>& query_ms) {
  using namespace cosmo;
  using namespace cosmo::place_recognition;
  std::vector<QueryOutcome> outcomes;
  ScanContextDatabase db(params.databaseParams());
  const auto excluded = static_cast<std::size_t>(params.exclude_recent);
  for (std::size_t i = 0; i < d.descriptors.size(); ++i) {
    bench::Stopwatch sw;
    const std::size_t searchable = i > excluded ? i - excluded : 0;
    const auto matches = db.query(d.descriptors[i], searchable);
    db.insert(i, d.descriptors[i]);
    query_ms.push_back(sw.elapsedMs());
    QueryOutcome o;
    for (std::size_t j = 0; j < searchable; ++j) {
      const double dist = (d.positions[j] - d.positions[i]).norm();
      if (o.nearest_separation < 0.0 || dist < o.nearest_separation) o.nearest_separation = dist;
    }
    if (!matches.empty()) {
      o.has_candidate = true;
      o.match = matches.front().id;
      o.distance = matches.front().match.distance;
      o.yaw = matches.front().match.yaw;
      o.match_separation = (d.positions[o.match] - d.positions[i]).norm();
    }
    outcomes.push_back(o);
    if (list) printOutcome(d, i, o);
  }
  return outcomes;
}

void printReport(const Options& o, const cosmo::place_recognition::PlaceRecognitionParams& params, const Described& d,
                 const std::vector<cosmo::place_recognition::QueryOutcome>& outcomes,
                 const std::vector<double>& query_ms) {
  using namespace cosmo;
  using namespace cosmo::place_recognition;
  std::printf("%zu scans (%.0f points on average) from %s, exclude_recent %d, revisit radius %.1f m\n",
              d.descriptors.size(), static_cast<double>(d.points) / d.descriptors.size(), o.positional[0].c_str(),
              params.exclude_recent, o.radius);
  std::printf("threshold  detections  true_pos  revisits  precision  recall\n");
  for (double t = o.lo; t <= o.hi + 1e-9; t += o.step) {
    const PrPoint p = precisionRecallAt(outcomes, t, o.radius);
    std::printf("%9.3f  %10zu  %8zu  %8zu  %9.3f  %6.3f%s\n", t, p.detections, p.true_positives, p.revisits,
                p.precision, p.recall, std::abs(t - params.threshold) < 1e-9 ? "   <- default" : "");
  }
  const PrPoint dp = precisionRecallAt(outcomes, params.threshold, o.radius);
  std::printf("default threshold %.3f: precision %.3f recall %.3f (%zu/%zu detections correct, %zu revisits)\n",
              params.threshold, dp.precision, dp.recall, dp.true_positives, dp.detections, dp.revisits);
  std::printf("descriptor time: median %.3f ms, p95 %.3f ms (point_stride %d)\n", bench::quantile(d.descriptor_ms, 0.5),
              bench::quantile(d.descriptor_ms, 0.95), params.sc.point_stride);
  std::printf("query+insert time: median %.3f ms, p95 %.3f ms, max %.3f ms (database of up to %zu entries)\n",
              bench::quantile(query_ms, 0.5), bench::quantile(query_ms, 0.95), bench::quantile(query_ms, 1.0),
              d.descriptors.size());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options o;
    if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
    const cosmo::place_recognition::PlaceRecognitionParams params = placeParams(o);
    const Described described = describeScans(o, params);
    std::vector<double> query_ms;
    const std::vector<cosmo::place_recognition::QueryOutcome> outcomes =
        searchIncrementally(described, params, o.list, query_ms);
    printReport(o, params, described, outcomes, query_ms);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_scancontext: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
