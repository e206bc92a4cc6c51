// bench_sim: ray-casting throughput of the simulated LiDAR and the time to make a whole sequence's scans.
//
//   bench_sim [--config config/sim/default.yaml] [--scans 100] [--sequence]
//
// Prints world build time, rays/s over --scans consecutive scans of the first trial (TBB on all cores), and
// with --sequence the core time to cast every scan of every trial (bag writing excluded; cosmo_simulate's
// own timing includes it).
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <sys/resource.h>

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"

using namespace cosmo;

namespace {
/// CPU seconds used by this process (all threads): rays per CPU second do not depend on other load.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
}  // namespace

int main(int argc, char** argv) {
  std::string config = std::string(COSMO_SOURCE_DIR) + "/config/sim/default.yaml";
  std::size_t scans = 100;
  bool sequence = false;
  int threads = 0;
  cosmo::CommandLine app("bench_sim",
                         "Ray-casting throughput of the simulated LiDAR and the time to make a whole sequence's "
                         "scans.");
  app.add_option("--config", config, "the simulation config")->type_name("FILE")->capture_default_str();
  app.add_option("--scans", scans, "consecutive scans of the first trial")->capture_default_str();
  app.add_option("--threads", threads, "TBB threads (0: all cores)")->capture_default_str();
  app.add_flag("--sequence", sequence, "also cast every scan of every trial");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  const int nthreads = threads > 0 ? threads : tbb::info::default_concurrency();
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, nthreads);
  const auto params = sim::SimulationParams::load(config);
  bench::Stopwatch sw;
  const auto seq = sim::planSequence(params);
  const double plan_s = sw.elapsedMs() * 1e-3;
  std::printf("config %s: world %zu primitives (BVH %zu nodes), %zu trials, planned in %.2f s, %d threads\n",
              config.c_str(), seq.world->objects().primitives().size(), seq.world->objects().nodeCount(),
              seq.trials.size(), plan_s, nthreads);
  sim::ScanSimulator simulator(*seq.world, params.lidar);
  const auto& t = seq.trials.front();
  const std::size_t n = std::min(scans, t.scan_stamps.size());
  // Scans from the middle of the trial (in the campus, not at the start pose).
  const std::size_t first = (t.scan_stamps.size() - n) / 2;
  std::size_t points = 0;
  sw.restart();
  double cpu0 = cpuSeconds();
  for (std::size_t k = first; k < first + n; ++k)
    points += simulator.simulate(t.body, t.params.extrinsicPose(), t.scan_stamps[k], t.noise_seed).size();
  const double sec = sw.elapsedMs() * 1e-3;
  const double cpu = cpuSeconds() - cpu0;
  const double rays = static_cast<double>(n) * params.lidar.raysPerScan();
  std::printf("ray casting: %zu scans of %s (%d x %d), %.2f s, %.2f M rays/s, %.1f ms/scan, %.0f points/scan\n", n,
              params.lidar.name.c_str(), params.lidar.beams, params.lidar.columns, sec, rays / sec * 1e-6,
              1e3 * sec / n, static_cast<double>(points) / n);
  std::printf("  CPU time %.2f s: %.2f M rays per CPU second (x %d threads = %.2f M rays/s without other load)\n", cpu,
              rays / cpu * 1e-6, nthreads, rays / cpu * 1e-6 * nthreads);
  if (sequence) {
    std::size_t total_scans = 0;
    sw.restart();
    cpu0 = cpuSeconds();
    for (const auto& tr : seq.trials) {
      for (auto s : tr.scan_stamps) simulator.simulate(tr.body, tr.params.extrinsicPose(), s, tr.noise_seed);
      total_scans += tr.scan_stamps.size();
    }
    const double seq_s = sw.elapsedMs() * 1e-3;
    const double seq_cpu = cpuSeconds() - cpu0;
    std::printf("sequence %s: %zu scans, casting %.1f s wall / %.1f s CPU (+ planning %.2f s), %.2f M rays/s\n",
                params.name.c_str(), total_scans, seq_s, seq_cpu, plan_s,
                total_scans * static_cast<double>(params.lidar.raysPerScan()) / seq_s * 1e-6);
  }
  return 0;
}
