// Back-end check and figure times (issue 25): `cosmo_jrl solve` on the reference COSMO-Bench file (1,025 poses,
// 1,661 factors; when ../shared exists) per factor selection, and both figures of a synthetic 5-robot dataset
// with about 2,000 loop closures. Targets: each well under a second.
//   bench_backend [--repeats N] [--png]
#include <time.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/synthetic.hpp"
#include "cosmo/report/figures.hpp"

using cosmo::bench::quantile;
using cosmo::bench::Stopwatch;
using namespace cosmo;

namespace {

/// CPU seconds of the calling thread (the figures below are single-threaded; wall time suffers from load).
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

void benchSolve(const std::string& path, int repeats) {
  const jrl::Dataset d = jrl::readJrl(path);
  std::printf("solve %s (%zu factors)\n", d.name.c_str(), jrl::computeStats(d).factors);
  for (auto s :
       {backend::FactorSelection::All, backend::FactorSelection::AllRobust, backend::FactorSelection::Inliers}) {
    std::vector<double> ms, cpu;
    backend::DatasetCheck check;
    for (int i = 0; i < repeats; ++i) {
      Stopwatch sw;
      const double c0 = threadCpuMs();
      check = backend::checkDataset(d, {s});
      cpu.push_back(threadCpuMs() - c0);
      ms.push_back(sw.elapsedMs());
    }
    const auto& c = check.solves.front();
    std::printf(
        "  %-8s CPU median %7.1f ms (min %.1f), wall median %.1f ms | %d iterations, cost %.1f -> %.1f | "
        "ATE %.3f m (init %.3f m), rot %.2f deg\n",
        backend::selectionName(s), quantile(cpu, 0.5), quantile(cpu, 0.0), quantile(ms, 0.5), c.solve.iterations,
        c.solve.initial_cost, c.solve.final_cost, c.error.overall.trans_m, check.init.overall.trans_m,
        c.error.overall.rot_rad * 180.0 / M_PI);
  }
}

void benchPlot(int repeats, bool png) {
  std::mt19937_64 rng(1);
  jrl::SyntheticParams p;
  p.robots = {'a', 'b', 'c', 'd', 'e'};
  p.poses_per_robot = 700;
  const jrl::Dataset d = jrl::makeSyntheticDataset(p, rng);
  const auto s = jrl::computeStats(d);
  std::printf("plot synthetic: %zu robots, %zu poses each, %zu loop closures (LC %zu, IRLC %zu)\n", p.robots.size(),
              p.poses_per_robot, s.lc_count + s.irlc_count, s.lc_count, s.irlc_count);
  const auto dir = std::filesystem::temp_directory_path() / "cosmo_bench_backend";
  std::filesystem::create_directories(dir);
  std::vector<double> ms, cpu;
  std::vector<std::string> written;
  for (int i = 0; i < repeats; ++i) {
    Stopwatch sw;
    const double c0 = threadCpuMs();
    written = report::writeDatasetFigures(d, (dir / "synthetic_5x700.jrl").string(), "", png);
    cpu.push_back(threadCpuMs() - c0);
    ms.push_back(sw.elapsedMs());
  }
  std::printf("  both figures%s: CPU median %.1f ms (min %.1f; this process only), wall median %.1f ms\n",
              png ? " with PNG (ImageMagick)" : " (SVG)", quantile(cpu, 0.5), quantile(cpu, 0.0), quantile(ms, 0.5));
  for (const auto& f : written)
    std::printf("  %s %.0f kB\n", f.c_str(), double(std::filesystem::file_size(f)) / 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  bool png = false;
  cosmo::CommandLine app("bench_backend",
                         "Back-end check and figure times: cosmo_jrl solve on the reference COSMO-Bench file per "
                         "factor selection, and both figures of a synthetic 5-robot dataset.");
  app.add_option("--repeats", repeats, "runs per figure (at least 1)")->capture_default_str();
  app.add_flag("--png", png, "also time the PNG conversion");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  repeats = std::max(1, repeats);
  try {
    if (const auto ref = sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl"))
      benchSolve(*ref, repeats);
    else
      std::printf("solve: ../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available, skipped\n");
    benchPlot(repeats, png);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_backend: %s\n", e.what());
    return 1;
  }
  return 0;
}
