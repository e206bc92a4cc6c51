// bench_trial_bags: CPU cost of reading one scan from each trial container — an MCD-layout ROS 1 bag with bz2
// chunks (first read: decompress, decode and fill the scan cache; later reads: the cache), the same bag
// uncompressed, and a CU-Multi-layout ROS 2 sqlite3 bag — for simulated organised Ouster sweeps of 64 x 1024 and
// 128 x 1024 (decompression + decode + invalid-return removal, one thread). The scan cache goes to the bench's
// folder.
//
//   bench_trial_bags [--scans N] [--beams 64,128] [--dir DIR]
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/bench/sim_trial.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/ros/bag_io.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/trials/cu_multi_layout.hpp"
#include "cosmo/trials/mcd_layout.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

struct ReadCost {
  double cpu_ms_per_scan = 0.0;
  double points_per_scan = 0.0;
};

ReadCost readAll(const sequence::TrialConfig& trial) {
  auto src = trials::openTrialScanSource(trial);
  Scan s;
  std::size_t n = 0, points = 0;
  const double c0 = bench::processCpuMs();
  while (src->next(s)) {
    ++n;
    points += s.size();
  }
  return {(bench::processCpuMs() - c0) / std::max<std::size_t>(1, n),
          static_cast<double>(points) / std::max<std::size_t>(1, n)};
}

double megabytes(const fs::path& p) {
  std::uintmax_t bytes = 0;
  if (fs::is_directory(p)) {
    for (const auto& e : fs::recursive_directory_iterator(p))
      if (e.is_regular_file()) bytes += e.file_size();
  } else {
    bytes = fs::file_size(p);
  }
  return static_cast<double>(bytes) / 1e6;
}

}  // namespace

int main(int argc, char** argv) {
  int scans = 30;
  std::vector<int> beam_counts{64, 128};
  fs::path dir = fs::temp_directory_path() / ("cosmo_bench_trial_bags_" + std::to_string(::getpid()));
  cosmo::CommandLine app("bench_trial_bags",
                         "CPU cost of reading one scan from each trial container (MCD bz2 bag first read and cached, "
                         "the bag uncompressed, a CU-Multi ROS 2 bag) for simulated Ouster sweeps.");
  app.add_option("--scans", scans, "scans per container")->capture_default_str();
  app.add_option("--beams", beam_counts, "LiDAR beams, comma separated")->delimiter(',')->capture_default_str();
  app.add_option("--dir", dir, "work folder (the scan cache goes there)")->type_name("DIR");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  fs::create_directories(dir);
  ::setenv("COSMO_SCAN_CACHE", (dir / "scan_cache").c_str(), 1);
  std::printf("%-9s %6s %8s %8s %8s %8s | %12s %12s %12s %12s | %8s  (ms: CPU per scan)\n", "sweep", "scans", "bz2 MB",
              "raw MB", "ros2 MB", "cache MB", "bz2 1st", "bz2 cached", "raw", "ros2", "pts/scan");
  for (int beams : beam_counts) {
    const sim::LidarModel lidar = bench::benchOuster(beams);
    const auto seq = bench::benchTrialPlan(lidar);
    const auto& t = seq.trials.at(0);
    sim::ScanSimulator simulator(*seq.world, lidar);
    const auto mcd_sweep = trials::mcdSweep(beams, lidar.columns, lidar.rate_hz);
    const auto cu_sweep = trials::cuMultiSweep(beams, lidar.columns, lidar.rate_hz);
    const fs::path bz2 = dir / ("os1_" + std::to_string(beams) + "_bz2.bag");
    const fs::path raw = dir / ("os1_" + std::to_string(beams) + "_raw.bag");
    const fs::path ros2 = dir / ("robot1_os1_" + std::to_string(beams) + "_lidar");
    {
      ros_glue::ScanBagWriter w_bz2(bz2.string(), ros_glue::BagCompression::Bz2);
      ros_glue::ScanBagWriter w_raw(raw.string(), ros_glue::BagCompression::None);
      trials::CuMultiBagWriter w_ros2(ros2.string(), 1);
      const int n = std::min<int>(scans, static_cast<int>(t.scan_stamps.size()));
      for (int k = 0; k < n; ++k) {
        const Scan s = simulator.simulate(t.body, t.params.extrinsicPose(), t.scan_stamps[k], t.noise_seed);
        w_bz2.write(trials::kMcdTopic, trials::organisedOusterCloud(s, mcd_sweep));
        w_raw.write(trials::kMcdTopic, trials::organisedOusterCloud(s, mcd_sweep));
        w_ros2.write(trials::organisedOusterCloud(s, cu_sweep));
      }
    }
    sequence::TrialConfig trial;
    trial.topic = trials::kMcdTopic;
    trial.bag = bz2.string();
    const ReadCost c_bz2 = readAll(trial);
    const ReadCost c_cached = readAll(trial);
    trial.bag = raw.string();
    const ReadCost c_raw = readAll(trial);
    trial.bag = ros2.string();
    trial.topic = trials::cuMultiTopic(1);
    trial.stamp_at_end = false;
    const ReadCost c_ros2 = readAll(trial);
    std::printf("%4d x %-4d %6d %8.1f %8.1f %8.1f %8.1f | %12.1f %12.1f %12.1f %12.1f | %8.0f\n", beams, lidar.columns,
                scans, megabytes(bz2), megabytes(raw), megabytes(ros2), megabytes(dir / "scan_cache"),
                c_bz2.cpu_ms_per_scan, c_cached.cpu_ms_per_scan, c_raw.cpu_ms_per_scan, c_ros2.cpu_ms_per_scan,
                c_bz2.points_per_scan);
    fs::remove_all(dir / "scan_cache");
    std::fflush(stdout);
  }
  fs::remove_all(dir);
  return 0;
}
