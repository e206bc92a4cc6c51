// cosmo_simulate: writes a synthetic multi-trial sequence (bags, ground truth and a sequence config) from a
// generation config, cached by a hash of all parameters, the layout and the code version. The layout is cosmo's
// own (one ROS 1 bag and one pose CSV per trial) or a real dataset's exactly (--layout mcd | cu-multi, see
// cosmo/ros/trial_layout_writer.hpp), so that the readers of those datasets can be checked against the truth. In
// cosmo's layout the clouds are Ouster's, or with --points another LiDAR's point layout (trials/point_layouts.hpp).
//
//   cosmo_simulate [--config config/sim/default.yaml | --small] [--layout cosmo|mcd|cu-multi]
//                  [--points ouster|velodyne|hesai|livox|livox-custom|split-time] [--out DIR]
//                  [--cache-dir DIR] [--no-cache] [--force] [--plan-only]
//
// The last line printed is the path of the sequence config.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/cache/cache.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/ros/bag_io.hpp"
#include "cosmo/ros/trial_layout_writer.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/trials/point_layouts.hpp"

namespace fs = std::filesystem;
using namespace cosmo;

namespace {

// Junctions and paths of the world, for choosing start nodes and waypoints:
// "junction,<index>,<x>,<y>" and "path,<junction a>,<junction b>,street|footpath,<length m>".
void writeNetworkCsv(const std::string& path, const sim::PathNetwork& net) {
  std::ofstream out(path);
  out << std::fixed << std::setprecision(1);
  for (std::size_t i = 0; i < net.nodes.size(); ++i)
    out << "junction," << i << ',' << net.nodes[i].x() << ',' << net.nodes[i].y() << '\n';
  for (std::size_t e = 0; e < net.edges.size(); ++e)
    out << "path," << net.edges[e].a << ',' << net.edges[e].b << ',' << (net.edges[e].street ? "street" : "footpath")
        << ',' << net.edgeLength(static_cast<int>(e)) << '\n';
  if (!out) throw std::runtime_error(path + ": write failed");
}

// The sequence config of a trial set written in a real layout (paths relative to the config's folder).
void writeLayoutSequenceConfig(const std::string& path, const sim::SimulationParams& params,
                               ros_glue::TrialLayout layout, const std::vector<ros_glue::WrittenTrial>& written) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write sequence config");
  out << std::setprecision(17);
  out << "# Synthetic sequence in the " << ros_glue::trialLayoutName(layout)
      << " layout, written by cosmo_simulate (code " << sim::kSimCodeVersion << ", parameter hash " << params.hash()
      << ")\n";
  if (layout == ros_glue::TrialLayout::CuMulti)
    out << "# ground truth positions carry a UTM-like offset: x + " << ros_glue::kSimulatedUtmOffset.x() << ", y + "
        << ros_glue::kSimulatedUtmOffset.y() << "\n";
  out << "name: " << params.name << "\nsource: " << params.source << "\nseed: " << params.seed
      << "\nanchor: " << params.anchor << "\ntime_offset_sigma: " << params.time_offset_sigma
      << "\nenvironment: " << params.environment << "\n";
  if (layout == ros_glue::TrialLayout::CuMulti) out << "reference_offset: anchor\n";  // one UTM frame, one offset
  out << "trials:\n";
  for (std::size_t i = 0; i < written.size(); ++i) {
    const auto& w = written[i];
    out << "  - robot: " << params.trials[i].robot << "\n    name: " << params.trials[i].name << "\n    bag: " << w.bag
        << "\n    topic: " << w.topic << "\n    reference: " << w.reference
        << "\n    stamp: " << (w.stamp_at_end ? "end" : "start") << "\n    extrinsic: [";
    const Eigen::Matrix4d M = w.extrinsic.matrix();
    for (int k = 0; k < 16; ++k) out << (k ? ", " : "") << M(k / 4, k % 4);
    out << "]\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

void generate(const sim::SimulationParams& params, const fs::path& dir, bool plan_only, ros_glue::TrialLayout layout,
              trials::PointLayout point_layout) {
  const bool own_layout = layout == ros_glue::TrialLayout::Cosmo;
  bench::Stopwatch total;
  std::cout << "planning world and routes (seed " << params.seed << ")..." << std::endl;
  const auto seq = sim::planSequence(params);
  const auto& world = *seq.world;
  std::printf("world: %zu primitives, path network %zu junctions / %.0f m, terrain %.0f x %.0f m (%.1f s)\n",
              world.objects().primitives().size(), world.network().nodes.size(), world.network().totalLength(),
              world.terrain().hi().x() - world.terrain().lo().x(), world.terrain().hi().y() - world.terrain().lo().y(),
              total.elapsedMs() * 1e-3);
  if (own_layout) sim::writeSequenceConfig((dir / (params.name + ".yaml")).string(), params);
  std::vector<ros_glue::WrittenTrial> written;
  int robot_number = 0;
  if (plan_only) writeNetworkCsv((dir / "network.csv").string(), world.network());
  for (const auto& t : seq.trials) {
    const auto& tp = t.params;
    std::printf("trial %s (robot %s, %s): %zu junctions, %.0f m, %.1f s, %zu scans\n", tp.name.c_str(),
                tp.robot.c_str(), tp.platform.c_str(), t.route.size(), t.body.length(),
                toSeconds(t.body.endStamp() - t.body.startStamp()), t.scan_stamps.size());
    std::printf("  route:");
    for (int n : t.route) std::printf(" %d", n);
    std::printf("\n");
    std::fflush(stdout);
    ++robot_number;
    if (own_layout) writeMcdPoseCsv((dir / (tp.name + "_pose_inW.csv")).string(), t.body);
    if (plan_only) continue;
    const sim::ScanSimulator simulator(*t.world, params.lidar);  // the world with this trial's clutter
    std::unique_ptr<ros_glue::ScanBagWriter> own_bag;
    std::unique_ptr<ros_glue::TrialLayoutWriter> layout_writer;
    if (own_layout) {
      own_bag = std::make_unique<ros_glue::ScanBagWriter>((dir / (tp.name + ".bag")).string());
    } else {
      ros_glue::LayoutTrialInfo info;
      info.name = tp.name;
      info.robot_number = robot_number;
      info.platform = tp.platform;
      info.beams = params.lidar.beams;
      info.columns = params.lidar.columns;
      info.rate_hz = params.lidar.rate_hz;
      layout_writer = ros_glue::makeTrialLayoutWriter(layout, dir.string(), info);
    }
    const Pose3 extrinsic = tp.extrinsicPose();
    bench::Stopwatch sw;
    std::size_t points = 0;
    std::future<void> pending;
    const std::size_t n = t.scan_stamps.size();
    for (std::size_t k = 0; k < n; ++k) {
      Scan scan = simulator.simulate(t.body, extrinsic, t.scan_stamps[k], t.noise_seed);
      points += scan.size();
      if (pending.valid()) pending.get();  // the previous scan is written while this one is cast
      pending =
          std::async(std::launch::async, [&own_bag, &layout_writer, &params, point_layout, s = std::move(scan)]() {
            if (own_bag)
              own_bag->write(params.topic, s, params.frame_id, point_layout);
            else
              layout_writer->write(s);
          });
      if ((k + 1) % std::max<std::size_t>(1, n / 10) == 0 || k + 1 == n) {
        const double sec = sw.elapsedMs() * 1e-3;
        std::printf("  %s: %zu/%zu scans, %.0f points/scan, %.2f M rays/s, %.1f s\n", tp.name.c_str(), k + 1, n,
                    static_cast<double>(points) / (k + 1),
                    (k + 1) * static_cast<double>(params.lidar.raysPerScan()) / std::max(sec, 1e-9) * 1e-6, sec);
        std::fflush(stdout);
      }
    }
    if (pending.valid()) pending.get();
    if (own_bag)
      own_bag->close();
    else
      written.push_back(layout_writer->finish(t.body, extrinsic));
  }
  if (!own_layout) writeLayoutSequenceConfig((dir / (params.name + ".yaml")).string(), params, layout, written);
  std::ofstream(dir / "parameters.txt") << params.describe() << "\n";
  std::printf("generated in %.1f s\n", total.elapsedMs() * 1e-3);
}

}  // namespace

int main(int argc, char** argv) {
  std::string config, out, cache_dir, layout_name = "cosmo", points_name = "ouster";
  bool small = false, no_cache = false, force = false, plan_only = false;
  cosmo::CommandLine app(
      "cosmo_simulate",
      "Writes a synthetic multi-trial sequence (bags, ground truth and a sequence config), cached by a "
      "hash of all parameters, the layout and the code version. The last line printed is the path of the "
      "sequence config.");
  app.add_option("--config", config, "generation parameters (default: config/sim/default.yaml of the source tree)")
      ->type_name("FILE");
  app.add_flag("--small", small, "use config/sim/ci.yaml (a CI-sized sequence)");
  app.add_option("--layout", layout_name,
                 "cosmo: <trial>.bag + <trial>_pose_inW.csv; mcd: <trial>/<trial>_os1_<beams>.bag (bz2, organised "
                 "Ouster clouds stamped at the sweep end), <trial>/pose_inW.csv (body, 10 Hz, from 1 s after the "
                 "first scan), calibration.yaml; cu-multi: robotN_<trial>_lidar/ (ROS 2 sqlite3 bag, clouds stamped "
                 "at the sweep start; the LiDAR runs at 20 Hz), <trial>_robotN_ref.csv (UTM-offset body poses)")
      ->capture_default_str();
  app.add_option("--points", points_name,
                 "the clouds' point layout in the cosmo layout (" + trials::pointLayoutNames() +
                     "; docs/data.md): each LiDAR's per-point time and ring fields, livox-custom a "
                     "livox_ros_driver/CustomMsg")
      ->capture_default_str();
  app.add_option("--out", out, "put the sequence here (symlinks into the cache, or real files with --no-cache)")
      ->type_name("DIR");
  app.add_option("--cache-dir", cache_dir,
                 "cache root (default: $COSMO_SIM_CACHE, else ~/.cache/cosmo/sim; at most "
                 "$COSMO_SIM_CACHE_MAX_SIZE, default 20G: least recently used sequences go first; `cosmo_cache`)")
      ->type_name("DIR");
  app.add_flag("--no-cache", no_cache, "generate straight into --out, do not read or fill the cache");
  app.add_flag("--force", force, "regenerate even when the cache holds this sequence");
  app.add_flag("--plan-only", plan_only,
               "write only the reference trajectories, the sequence config and network.csv (junctions and paths, "
               "for choosing start_node / waypoints) into --out (preview)");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  if (config.empty())
    config = std::string(COSMO_SOURCE_DIR) + (small ? "/config/sim/ci.yaml" : "/config/sim/default.yaml");
  if ((no_cache || plan_only) && out.empty()) {
    std::cerr << "--no-cache and --plan-only need --out DIR\n";
    return 2;
  }
  try {
    const ros_glue::TrialLayout layout = ros_glue::parseTrialLayout(layout_name);
    if (plan_only && layout != ros_glue::TrialLayout::Cosmo)
      throw std::runtime_error("--plan-only writes the cosmo layout only");
    const std::optional<trials::PointLayout> points = trials::parsePointLayout(points_name);
    if (!points) throw std::runtime_error("--points " + points_name + ": not one of " + trials::pointLayoutNames());
    const bool ouster = *points == trials::PointLayout::Ouster;
    if (!ouster && layout != ros_glue::TrialLayout::Cosmo)
      throw std::runtime_error("--points " + points_name + ": the " + layout_name +
                               " layout holds Ouster clouds; other point layouts go in the cosmo layout");
    auto params = sim::SimulationParams::load(config);
    if (layout == ros_glue::TrialLayout::CuMulti) params.lidar.rate_hz = 20.0;  // CU-Multi's Ouster runs at 20 Hz
    const std::string key = params.name + "-" + params.hash() +
                            (layout == ros_glue::TrialLayout::Cosmo ? "" : "-" + layout_name) +
                            (ouster ? "" : "-" + points_name);
    const fs::path cache = cache_dir.empty() ? cache::cacheRoot(cache::Kind::Sim) : fs::path(cache_dir);
    if (plan_only) no_cache = true;
    if (!no_cache) cache::maxSize(cache::Kind::Sim);  // a bad limit is an error before the generation
    const fs::path final_dir = no_cache ? fs::path(out) : cache / key;
    const std::string seq_name = params.name + ".yaml";
    std::optional<cache::EntryUse> in_use;  // not removed by another process's limit while linked into --out
    if (!no_cache && !force && fs::exists(final_dir / "COMPLETE")) {
      in_use.emplace(final_dir);
      if (!fs::exists(final_dir / cache::kFolderInfoName))  // written before entries were described
        cache::writeInfo(final_dir / cache::kFolderInfoName,
                         "sequence " + params.name + " (" + layout_name + " layout) from " + config);
      cache::touch(final_dir);  // used now: evicted last
      std::cout << "cache hit: " << final_dir.string() << std::endl;
    } else {
      fs::path tmp = no_cache ? final_dir : fs::path(final_dir.string() + ".tmp-" + std::to_string(::getpid()));
      fs::create_directories(tmp);
      std::cout << "generating " << params.name << " (" << config << ") into " << final_dir.string() << std::endl;
      generate(params, tmp, plan_only, layout, *points);
      if (!plan_only) std::ofstream(tmp / "COMPLETE") << key << "\n";
      if (!no_cache) {
        cache::writeInfo(tmp / cache::kFolderInfoName,
                         "sequence " + params.name + " (" + layout_name + " layout) from " + config);
        if (fs::exists(final_dir / "COMPLETE")) {
          fs::remove_all(tmp);  // another run finished the same sequence meanwhile: keep its files
        } else {
          fs::remove_all(final_dir);
          fs::rename(tmp, final_dir);
        }
        in_use.emplace(final_dir);
        cache::touch(final_dir);
        cache::applyLimit(cache::Kind::Sim, cache, key);
      }
    }
    fs::path seq_path = final_dir / seq_name;
    if (!no_cache && !out.empty()) {  // link the cached files into --out
      fs::create_directories(out);
      for (const auto& e : fs::directory_iterator(final_dir)) {
        if (e.path().filename() == cache::kFolderInfoName) continue;  // the cache's, not the sequence's
        // made beside and renamed over the old one: several processes may link the same sequence at once
        const fs::path link = fs::path(out) / e.path().filename();
        const fs::path tmp_link =
            fs::path(out) / (e.path().filename().string() + ".link-" + std::to_string(::getpid()));
        std::error_code ec;
        fs::remove(tmp_link, ec);
        fs::create_symlink(fs::absolute(e.path()), tmp_link);
        fs::rename(tmp_link, link);
      }
      seq_path = fs::path(out) / seq_name;
    }
    std::cout << fs::absolute(seq_path).string() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "cosmo_simulate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
