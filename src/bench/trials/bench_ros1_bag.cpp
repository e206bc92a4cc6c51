// bench_ros1_bag: the two ways to read ROS 1 bags safely, measured on real-layout fixtures (simulated organised
// Ouster sweeps written as MCD writes them: topic /os_cloud_node/points, chunks bz2, none or lz4):
//   librosbag             rosbag::View, as cosmo read bags (it crashes on damaged records: the reference only)
//   check + librosbag     a bounds-checked pass over every record and chunk first (cosmo's reader without the
//                         decode), then librosbag: what "validate before librosbag sees it" costs at least
//   own, N workers        cosmo's bounds-checked reader (trials::Ros1ScanSource), chunks decompressed on N threads
// Each variant reads every scan once (decompression + decode: a first pass, no scan cache) in a child process of
// its own: wall and CPU ms per scan, peak RSS. Every variant's scans are compared bit for bit with librosbag's.
//
//   bench_ros1_bag [--scans N] [--beams 64] [--workers 0,1,2,4] [--dir DIR]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/bench/sim_trial.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/ros/bag_io.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/trials/mcd_layout.hpp"
#include "cosmo/trials/ouster_cloud.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros1_message_stream.hpp"
#include "cosmo/trials/trial_scans.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

/// A digest of every scan's bytes (FNV-1a), to compare the variants' outputs.
struct Digest {
  std::uint64_t h = 1469598103934665603ull;
  std::size_t scans = 0;
  void add(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  void add(const Scan& s) {
    add(&s.stamp, sizeof s.stamp);
    add(s.points.data(), s.points.size() * sizeof(s.points[0]));
    add(s.intensity.data(), s.intensity.size() * sizeof(float));
    add(s.time.data(), s.time.size() * sizeof(float));
    add(s.ring.data(), s.ring.size() * sizeof(std::uint16_t));
    ++scans;
  }
};

struct Result {
  double wall_ms = 0, cpu_ms = 0, rss_mb = 0;
  std::uint64_t digest = 0;
  std::size_t scans = 0;
};

/// Runs `read` in a child process: its wall and CPU time and peak RSS, and the digest it returns.
Result inChild(const std::function<Digest()>& read) {
  int pipefd[2];
  if (::pipe(pipefd) != 0) throw std::runtime_error("pipe");
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipefd[0]);
    Result r;
    const double c0 = bench::processCpuMs();
    bench::Stopwatch sw;
    const Digest d = read();
    r.wall_ms = sw.elapsedMs();
    r.cpu_ms = bench::processCpuMs() - c0;
    r.digest = d.h;
    r.scans = d.scans;
    if (::write(pipefd[1], &r, sizeof r) != sizeof r) ::_exit(1);
    ::_exit(0);
  }
  ::close(pipefd[1]);
  Result r;
  const bool got = ::read(pipefd[0], &r, sizeof r) == sizeof r;
  ::close(pipefd[0]);
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  if (!got || !WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("a reader failed");
  r.rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  return r;
}

Digest readLibrosbag(const std::string& bag) {
  ros_glue::RosbagScanReader reader(bag, trials::kMcdTopic);
  Digest d;
  Scan s;
  while (reader.next(s)) d.add(s);
  return d;
}

/// What a validator must do before librosbag may read: every record's framing, every chunk decompressed and every
/// indexed message's record checked (cosmo's reader, without decoding the messages).
void checkEveryRecord(const std::string& bag_path) {
  auto bag = std::make_shared<const trials::Ros1Bag>(bag_path);
  std::vector<std::uint32_t> ids;
  for (const auto& c : bag->connections()) ids.push_back(c.id);
  trials::Ros1MessageStream stream(bag, bag->messages(ids), 0);
  trials::Ros1MessageRef m;
  trials::Ros1Bag::Bytes bytes;
  while (stream.next(m, bytes)) {}
}

Digest readOwn(const std::string& bag, int workers) {
  trials::Ros1ScanSource source(bag, trials::kMcdTopic, true, workers);
  Digest d;
  Scan s;
  while (source.next(s)) d.add(s);
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  int scans = 40;
  std::vector<int> beam_counts{64}, workers{0, 1, 2, 4};
  fs::path dir = fs::temp_directory_path() / ("cosmo_bench_ros1_bag_" + std::to_string(::getpid()));
  CommandLine app("bench_ros1_bag",
                  "Reads simulated MCD-layout bags (chunks bz2, none, lz4) with librosbag, with a record check before "
                  "librosbag, and with cosmo's own reader on N decompression workers: ms per scan, peak RSS.");
  app.add_option("--scans", scans, "scans per bag")->capture_default_str()->check(Positive);
  app.add_option("--beams", beam_counts, "LiDAR beams (64 or 128), comma separated")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--workers", workers, "decompression workers of the own reader, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--dir", dir, "where the bags are written (default: a temporary folder, removed at the end)");
  if (const auto code = app.parseOrExit(argc, argv)) return *code;
  fs::create_directories(dir);
  std::printf("%-12s %-6s %6s %-22s %9s %9s %8s  %s\n", "sweep", "chunks", "MB", "reader", "wall/scan", "CPU/scan",
              "peak MB", "scans = librosbag's");
  for (int beams : beam_counts) {
    const sim::LidarModel lidar = bench::benchOuster(beams);
    const auto seq = bench::benchTrialPlan(lidar);
    const auto& t = seq.trials.at(0);
    sim::ScanSimulator simulator(*seq.world, lidar);
    const auto sweep = trials::mcdSweep(beams, lidar.columns, lidar.rate_hz);
    std::vector<std::pair<std::string, ros_glue::BagCompression>> kinds{{"bz2", ros_glue::BagCompression::Bz2},
                                                                        {"none", ros_glue::BagCompression::None},
                                                                        {"lz4", ros_glue::BagCompression::Lz4}};
    for (const auto& [kind, compression] : kinds) {
      const fs::path bag = dir / ("os1_" + std::to_string(beams) + "_" + kind + ".bag");
      {
        ros_glue::ScanBagWriter writer(bag.string(), compression);
        const int n = std::min<int>(scans, static_cast<int>(t.scan_stamps.size()));
        for (int k = 0; k < n; ++k) {
          const Scan s = simulator.simulate(t.body, t.params.extrinsicPose(), t.scan_stamps[k], t.noise_seed);
          writer.write(trials::kMcdTopic, trials::organisedOusterCloud(s, sweep));
        }
      }
      const std::string sweep_name = std::to_string(beams) + " x " + std::to_string(lidar.columns);
      const double mb = static_cast<double>(fs::file_size(bag)) / 1e6;
      const Result ref = inChild([&] { return readLibrosbag(bag.string()); });
      auto row = [&](const std::string& name, const Result& r) {
        std::printf("%-12s %-6s %6.1f %-22s %9.1f %9.1f %8.0f  %s\n", sweep_name.c_str(), kind.c_str(), mb,
                    name.c_str(), r.wall_ms / r.scans, r.cpu_ms / r.scans, r.rss_mb,
                    r.digest == ref.digest && r.scans == ref.scans ? "yes" : "NO");
        std::fflush(stdout);
      };
      row("librosbag", ref);
      row("check + librosbag", inChild([&] {
            checkEveryRecord(bag.string());
            return readLibrosbag(bag.string());
          }));
      for (int w : workers)
        row("own, " + std::to_string(w) + " workers", inChild([&] { return readOwn(bag.string(), w); }));
    }
  }
  fs::remove_all(dir);
  return 0;
}
