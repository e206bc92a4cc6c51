// bench_comm: measured figures of the radio model and the scan payload.
//   1. connectivity frequency of an active link vs phi(d) (Wi-Fi, Pro-Radio)
//   2. clean-link throughput vs B * P_max; two overlapping links vs B * P_max / 2
//   3. a pair moving apart: time from losing connectivity to the timeout
//   4. liblzma compression ratio of real scans (../shared/data/scan_snippets) vs the paper's 0.653 +- 0.04,
//      and the time to compress / decompress a 64 x 1024 scan
//   5. simulator step cost with 3, 10 and 30 robots
// Usage: bench_comm [--samples N] [--seconds S]   (wall-clock timings; run on an idle machine for final figures)
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <random>
#include <string>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/scan_compression.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"

using namespace cosmo;

namespace {

constexpr std::size_t kHuge = 1000000000000ULL;

comm::RadioSimulator endlessPair(comm::RadioParams p, std::uint64_t seed) {
  p.size_model = comm::RadioParams::SizeModel::RealCompressed;
  p.timeout = 1e9;
  comm::RadioSimulator sim(p, {'a', 'b'}, seed);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {1, 0, 0}, true);
  sim.offerKeyframe('a', 0, kHuge);
  while (sim.activeCommunications().empty()) sim.step(sim.nextStepTime());
  return sim;
}

void connectivity(int n) {
  std::printf("\n## 1. Connectivity frequency of an active link vs phi(d)  (%d samples per distance)\n", n);
  std::printf("| model | d (m) | phi(d) | observed | sigma | z |\n|---|---|---|---|---|---|\n");
  for (const auto& [name, p] :
       {std::pair{"Wi-Fi", comm::RadioParams::wifi()}, std::pair{"Pro-Radio", comm::RadioParams::proRadio()}}) {
    for (double frac : {0.05, 0.2, 0.4, 0.6, 0.8, 0.95, 1.1}) {
      const double d = frac * p.r_max;
      comm::RadioSimulator sim = endlessPair(p, 100 + static_cast<int>(frac * 100));
      sim.setRobotState('b', {d, 0, 0}, true);
      const comm::RadioStats before = sim.stats();
      for (int i = 0; i < n; ++i) sim.step(sim.nextStepTime());
      const double m = sim.stats().link_samples - before.link_samples;
      const double f = (sim.stats().link_successes - before.link_successes) / m;
      const double phi = p.phi(d), sigma = std::sqrt(phi * (1 - phi) / m);
      std::printf("| %s | %.1f | %.4f | %.4f | %.4f | %+.2f |\n", name, d, phi, f, sigma,
                  sigma > 0 ? (f - phi) / sigma : 0.0);
    }
  }
}

void throughput(int n) {
  std::printf(
      "\n## 2. Throughput  (%d steps)\n| model | case | per-link mean (kB/s) | expected (kB/s) | ratio "
      "|\n|---|---|---|---|---|\n",
      n);
  for (const auto& [name, base] :
       {std::pair{"Wi-Fi", comm::RadioParams::wifi()}, std::pair{"Pro-Radio", comm::RadioParams::proRadio()}}) {
    comm::RadioSimulator sim = endlessPair(base, 5);
    const double b0 = sim.activeCommunications().front().bytes_delivered;
    for (int i = 0; i < n; ++i) sim.step(sim.nextStepTime());
    const double rate = (sim.activeCommunications().front().bytes_delivered - b0) / (n * base.step) / 1000;
    const double want = base.bandwidth_kBps * base.p_max;
    std::printf("| %s | clean link | %.1f | %.1f (B P_max) | %.4f |\n", name, rate, want, rate / want);
    for (double sep : {3.0, 10 * base.d_intf}) {
      comm::RadioParams p = base;
      p.size_model = comm::RadioParams::SizeModel::RealCompressed;
      p.timeout = 1e9;
      comm::RadioSimulator s(p, {'a', 'b', 'c', 'd'}, 9);
      const Eigen::Vector3d pos[4] = {{0, 0, 0}, {2, 0, 0}, {0, sep, 0}, {2, sep, 0}};
      for (int i = 0; i < 4; ++i) {
        s.setRobotState(static_cast<char>('a' + i), pos[i], true);
        s.offerKeyframe(static_cast<char>('a' + i), 0, kHuge);
      }
      while (s.activeCommunications().size() < 2) s.step(s.nextStepTime());
      std::vector<double> before;
      for (const auto& c : s.activeCommunications()) before.push_back(c.bytes_delivered);
      for (int i = 0; i < n; ++i) s.step(s.nextStepTime());
      double mean = 0;
      for (int i = 0; i < 2; ++i)
        mean += (s.activeCommunications()[i].bytes_delivered - before[i]) / (n * p.step) / 1000 / 2;
      const double expect = sep < p.d_intf ? want / 2 : want;
      std::printf("| %s | two links %.0f m apart (%s) | %.1f | %.1f | %.4f |\n", name, sep,
                  sep < p.d_intf ? "overlap, B/2" : "apart, B", mean, expect, mean / expect);
    }
  }
}

void timeouts(int trials) {
  std::printf("\n## 3. A pair moving apart at 2 m/s from 5 m (%d seeds, no_progress T = 2 s)\n", trials);
  for (const auto& [name, base] :
       {std::pair{"Wi-Fi", comm::RadioParams::wifi()}, std::pair{"Pro-Radio", comm::RadioParams::proRadio()}}) {
    comm::RadioParams p = base;
    p.size_model = comm::RadioParams::SizeModel::RealCompressed;
    double sum_d = 0, sum_gap = 0;
    int timed_out = 0;
    for (int s = 0; s < trials; ++s) {
      comm::RadioSimulator sim(p, {'a', 'b'}, s);
      sim.offerKeyframe('a', 0, kHuge);
      double d = 5.0;
      for (int i = 0; i < 100000; ++i, d += 2.0 * p.step) {
        sim.setRobotState('a', {0, 0, 0}, true);
        sim.setRobotState('b', {d, 0, 0}, true);
        const auto ended = sim.step(sim.nextStepTime());
        if (!ended.empty()) {
          timed_out += ended[0].outcome == comm::Transfer::Outcome::TimedOut;
          sum_d += d;
          sum_gap += d - p.r_max;
          break;
        }
      }
    }
    std::printf("- %s: %d/%d timed out; mean distance at timeout %.1f m (r_max %.0f m, phi = 0 beyond)\n", name,
                timed_out, trials, sum_d / trials, p.r_max);
  }
}

/// KITTI HDL-64E scan re-ordered as an organized 64 x 1024 grid (row-major, (0,0,0) where no return), the
/// shape of an Ouster OS1-64 cloud.
Scan organize64x1024(const Scan& in) {
  Scan out;
  out.points.assign(64 * 1024, Eigen::Vector3f::Zero());
  std::vector<float> best(64 * 1024, 1e9f);
  for (const auto& p : in.points) {
    const float r = p.norm();
    if (!(r > 0.5f)) continue;
    const float el = std::asin(p.z() / r) * 180.0f / static_cast<float>(M_PI);
    const int row = static_cast<int>(std::floor((2.0f - el) / 26.9f * 64.0f));
    const float az = std::atan2(p.y(), p.x());
    const int col =
        static_cast<int>(std::floor((az + static_cast<float>(M_PI)) / (2.0f * static_cast<float>(M_PI)) * 1024.0f)) %
        1024;
    if (row < 0 || row >= 64) continue;
    const int i = row * 1024 + col;
    if (r < best[i]) {
      best[i] = r;
      out.points[i] = p;
    }
  }
  return out;
}

struct Ratio {
  std::vector<double> r;
  void add(double x) { r.push_back(x); }
  double mean() const {
    double s = 0;
    for (double x : r) s += x;
    return s / r.size();
  }
  double sd() const {
    const double m = mean();
    double s = 0;
    for (double x : r) s += (x - m) * (x - m);
    return r.size() > 1 ? std::sqrt(s / (r.size() - 1)) : 0;
  }
};

void compression(int repeats) {
  std::printf("\n## 4. liblzma (xz preset 6) on real scans: compressed / raw (12 B per point), paper 0.653 +- 0.04\n");
  const auto root = sharedPath("data/scan_snippets");
  if (!root) {
    std::printf("(skipped: ../shared/data/scan_snippets not found)\n");
    return;
  }
  struct Set {
    const char* name;
    std::string folder;
    bool organize;
  };
  const std::vector<Set> sets = {
      {"KITTI 00 HDL-64E (.bin, unorganized ~120k pts)", *root + "/kitti00/velodyne", false},
      {"KITTI 00 as organized 64x1024 grid (zeros = no return)", *root + "/kitti00/velodyne", true},
      {"MulRan KAIST03 OS1-64 keyframes (.pcd, downsampled ~37k)", *root + "/mulran_kaist03_keyframes/Scans", false},
      {"hdl32 pair (.pcd, ~69k)", *root + "/hdl32_pair", false},
      {"KITTI 07 keyframes (xyz .bin, downsampled)", *root + "/kitti07_keyframes", false}};
  std::printf(
      "| data | scans | points (mean) | ratio mean | ratio sd | compress wall ms (median) | compress CPU ms | "
      "decompress wall ms |\n|---|---|---|---|---|---|---|---|\n");
  for (const Set& s : sets) {
    Ratio ratio;
    std::vector<double> tc, td, cc;
    double pts = 0;
    const auto files = listScanFiles(s.folder);
    for (const auto& f : files) {
      Scan scan = readScanFile(f);
      if (s.organize) scan = organize64x1024(scan);
      pts += scan.size();
      std::vector<std::uint8_t> bytes;
      for (int k = 0; k < repeats; ++k) {
        bench::Stopwatch w;
        const std::clock_t c0 = std::clock();
        bytes = comm::compressScan(scan);
        cc.push_back(1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
        tc.push_back(w.elapsedMs());
        w.restart();
        const Scan back = comm::decompressScan(bytes);
        td.push_back(w.elapsedMs());
        if (back.size() != scan.size()) std::printf("ROUND TRIP FAILED on %s\n", f.c_str());
      }
      ratio.add(static_cast<double>(bytes.size()) / comm::rawPayloadBytes(scan));
    }
    std::printf("| %s | %zu | %.0f | %.3f | %.3f | %.1f | %.1f | %.1f |\n", s.name, files.size(), pts / files.size(),
                ratio.mean(), ratio.sd(), bench::quantile(tc, 0.5), bench::quantile(cc, 0.5), bench::quantile(td, 0.5));
  }
  // The 64 x 1024 case: compression time of an organized grid at every xz preset.
  const Scan grid = organize64x1024(readScanFile(*root + "/kitti00/velodyne/000000.bin"));
  std::printf("\n64 x 1024 organized scan (KITTI 00 000000 re-gridded, 786432 B raw), by xz preset:\n");
  std::printf("| preset | ratio | compress wall ms (median of %d) | compress CPU ms (median) |\n|---|---|---|---|\n",
              repeats);
  for (std::uint32_t preset : {0u, 1u, 3u, 6u, 9u}) {
    std::vector<double> t, cpu;
    std::size_t size = 0;
    for (int k = 0; k < repeats; ++k) {
      bench::Stopwatch w;
      const std::clock_t c0 = std::clock();
      size = comm::compressScan(grid, preset).size();
      cpu.push_back(1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
      t.push_back(w.elapsedMs());
    }
    std::printf("| %u | %.3f | %.1f | %.1f |\n", preset, static_cast<double>(size) / comm::rawPayloadBytes(grid),
                bench::quantile(t, 0.5), bench::quantile(cpu, 0.5));
  }
}

void stepCost(double seconds) {
  std::printf(
      "\n## 5. Simulator step cost (%.0f s of simulated time per run, robots in random walks in a 300 m square,\n"
      "##    a keyframe every 2 s per robot, paper size model with S = 786432 B)\n",
      seconds);
  std::printf(
      "| model | robots | steps | wall us per step | CPU us per step | delivered | timed out "
      "|\n|---|---|---|---|---|---|---|\n");
  for (const auto& [name, p] :
       {std::pair{"Wi-Fi", comm::RadioParams::wifi()}, std::pair{"Pro-Radio", comm::RadioParams::proRadio()}}) {
    for (int n : {3, 10, 30}) {
      std::vector<char> ids;
      for (int i = 0; i < n; ++i) ids.push_back(static_cast<char>(i < 26 ? 'a' + i : 'A' + i - 26));
      comm::RadioSimulator sim(p, ids, 1);
      std::mt19937_64 rng(2);
      std::uniform_real_distribution<double> u(-150, 150), turn(-0.3, 0.3);
      std::vector<Eigen::Vector3d> pos(n);
      std::vector<double> heading(n);
      for (int i = 0; i < n; ++i) {
        pos[i] = {u(rng), u(rng), 0};
        heading[i] = u(rng);
      }
      const int steps = static_cast<int>(seconds / p.step);
      bench::Stopwatch w;
      const std::clock_t c0 = std::clock();
      for (int k = 0; k < steps; ++k) {
        for (int i = 0; i < n; ++i) {
          heading[i] += turn(rng);
          pos[i] += 0.15 * Eigen::Vector3d(std::cos(heading[i]), std::sin(heading[i]), 0);  // 1.5 m/s
          pos[i] = pos[i].cwiseMax(-150).cwiseMin(150);
          sim.setRobotState(ids[i], pos[i], true);
          if (k % 20 == 0) sim.offerKeyframe(ids[i], k / 20, 0, 786432);
        }
        sim.step(sim.nextStepTime());
      }
      const double ms = w.elapsedMs();
      const double cpu_ms = 1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      std::printf("| %s | %d | %d | %.2f | %.2f | %llu | %llu |\n", name, n, steps, 1000.0 * ms / steps,
                  1000.0 * cpu_ms / steps, static_cast<unsigned long long>(sim.stats().delivered),
                  static_cast<unsigned long long>(sim.stats().timed_out));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int samples = 20000;
  double seconds = 3600;
  cosmo::CommandLine app("bench_comm",
                         "Measured figures of the radio model and the scan payload (wall-clock timings; run on an "
                         "idle machine for final figures).");
  app.add_option("--samples", samples, "connectivity and throughput samples")->capture_default_str();
  app.add_option("--seconds", seconds, "simulated seconds of the step-cost runs")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  std::printf("# bench_comm (wall-clock timings; figures depend on machine load)\n");
  connectivity(samples);
  throughput(samples);
  timeouts(200);
  compression(5);
  stepCost(seconds);
  return 0;
}
