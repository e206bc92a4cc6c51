// bench_sequence_speed: a whole 3-robot sequence in MCD's layout (bz2 ROS 1 bags, organised Ouster clouds, 10 Hz
// body ground truth starting late) through the offline driver, as a user runs it: `cosmo_simulate --layout mcd`
// writes the sequence (cached by cosmo_simulate), then `cosmo_generate` runs it three times:
//   off    COSMO_SCAN_CACHE=off: every run decompresses the bz2 chunks;
//   first  an empty scan cache: the run decompresses and fills it (the one-time cost);
//   warm   the same cache again: scans and spans read from it.
// For each: wall time, CPU time of cosmo_generate (user + system, all threads), the real-time factor (sequence
// duration / wall) and CPU-seconds per sequence-second (the load-independent figure: on 2 idle cores a run can
// reach at most 2 / that real time), the scan cache's size, and whether the three JRLs are byte-identical.
// The machine's load average is printed with each run: wall times on a loaded machine are pessimistic.
//
//   bench_sequence_speed [--beams 64,128] [--runs off,first,warm] [--dir DIR] [--sim-cache DIR] [--comm wifi]
//                        [--short]
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/whole_file.hpp"
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

fs::path programDir() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path(".") : self.parent_path();
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  in >> one;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", one);
  return buf;
}

/// The simulator's configuration: the demo's campus (config/sim/default.yaml's world and seed) with three robots on
/// its central block: a walker along two sides (101 s), two ATVs one lap each in opposite directions (81 / 85 s);
/// `short`: three ATVs along one side each (23-27 s), for a machine too loaded to write the long one (writing a
/// bz2 bag costs ~0.3 s of CPU per 64 x 1024 scan).
std::string simName(int beams, bool short_routes) {
  return std::string(short_routes ? "bench_short_" : "bench_seq_") + std::to_string(beams);
}

void writeSimConfig(const fs::path& path, int beams, bool short_routes) {
  const std::string b = std::to_string(beams);
  const std::string prefix = short_routes ? "short_" + b + "_" : "bench_" + b + "_";
  std::ofstream out(path);
  out << "# bench_sequence_speed: 3 robots in MCD's layout, " << b << "-beam Ouster\n"
      << "name: " << simName(beams, short_routes) << "\nsource: synthetic\nenvironment: synthetic\nseed: 7\n"
      << "anchor: a\ntime_offset_sigma: 5.0\n"
      << "world:\n  blocks_x: 3\n  blocks_y: 3\n  block_min: 55.0\n  block_max: 75.0\n"
      << "lidar:\n  model: os1_" << b << "\n"
      << "trials:\n";
  auto trial = [&](char robot, const char* platform, int start, const char* waypoints, double speed) {
    out << "  - robot: " << robot << "\n    name: " << prefix << robot << "\n    platform: " << platform
        << "\n    start_node: " << start << "\n    waypoints: " << waypoints << "\n";
    if (speed > 0) out << "    motion:\n      cruise_speed: " << speed << "\n";
  };
  if (short_routes) {
    trial('a', "atv", 9, "[5]", 4.0);
    trial('b', "atv", 10, "[9]", 4.0);
    trial('c', "atv", 5, "[6]", 3.5);
  } else {
    trial('a', "handheld", 9, "[5, 6]", 0.0);
    trial('b', "atv", 10, "[9, 5, 6, 10]", 4.0);
    trial('c', "atv", 5, "[6, 10, 9, 5]", 3.5);
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

struct Run {
  int status = -1;
  double wall_s = 0.0, cpu_s = 0.0;
  std::string output;
};

/// Runs `argv` with `env` added, stdout + stderr to `log`; wall time and the child's CPU time (wait4).
Run runProgram(const std::vector<std::string>& argv, const std::vector<std::string>& env, const fs::path& log) {
  Run r;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    for (const auto& e : env) ::putenv(const_cast<char*>(e.c_str()));
    std::FILE* f = std::fopen(log.c_str(), "w");
    if (f) {
      ::dup2(fileno(f), 1);
      ::dup2(fileno(f), 2);
    }
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    std::_Exit(127);
  }
  int status = 0;
  struct rusage ru {};
  ::wait4(pid, &status, 0, &ru);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu_s = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
            1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = cosmo::readWholeFileOrEmpty(log);
  return r;
}

double directoryMb(const fs::path& dir) {
  std::uintmax_t bytes = 0;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return 0.0;
  for (const auto& e : fs::recursive_directory_iterator(dir, ec))
    if (e.is_regular_file()) bytes += e.file_size();
  return static_cast<double>(bytes) / 1e6;
}

bool sameBytes(const fs::path& a, const fs::path& b) {
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  if (!fa || !fb) return false;
  return std::equal(std::istreambuf_iterator<char>(fa), std::istreambuf_iterator<char>(),
                    std::istreambuf_iterator<char>(fb), std::istreambuf_iterator<char>());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> beam_counts{64, 128};
  std::vector<std::string> runs{"off", "first", "warm"};
  fs::path dir = fs::temp_directory_path() / "cosmo_bench_sequence_speed";
  std::string sim_cache, comm = "wifi";
  bool short_routes = false;
  cosmo::CommandLine app("bench_sequence_speed",
                         "A whole 3-robot sequence in MCD's layout through the offline driver, with the scan cache "
                         "off, first filled and warm: wall and CPU time, real-time factor, CPU-seconds per "
                         "sequence-second, cache size, and whether the JRLs are byte-identical.");
  app.add_option("--beams", beam_counts, "LiDAR beams, comma separated")->delimiter(',')->capture_default_str();
  app.add_option("--runs", runs, "off, first and / or warm, comma separated")->delimiter(',')->capture_default_str();
  app.add_option("--dir", dir, "work folder")->capture_default_str();
  app.add_option("--sim-cache", sim_cache, "cosmo_simulate's cache root (default: its own)")->type_name("DIR");
  app.add_option("--comm", comm, "the comm model")->capture_default_str();
  app.add_flag("--short", short_routes, "short routes (a quick look)");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  try {
    const fs::path bin = programDir();
    fs::create_directories(dir);
    std::printf("%-6s %-6s %9s %9s %9s %11s %9s %6s  %s\n", "beams", "run", "wall s", "CPU s", "x real", "CPU-s/seq-s",
                "cache MB", "load", "JRL");
    for (int beams : beam_counts) {
      const std::string name = simName(beams, short_routes);
      const fs::path sim_config = dir / (name + ".sim.yaml");
      writeSimConfig(sim_config, beams, short_routes);
      std::vector<std::string> sim{(bin / "cosmo_simulate").string(), "--config", sim_config.string(), "--layout",
                                   "mcd"};
      if (!sim_cache.empty()) sim.insert(sim.end(), {"--cache-dir", sim_cache});
      const Run simulated = runProgram(sim, {}, dir / ("simulate_" + std::to_string(beams) + ".log"));
      if (simulated.status != 0) throw std::runtime_error("cosmo_simulate failed:\n" + simulated.output);
      std::string sequence = simulated.output.substr(0, simulated.output.find_last_not_of("\n") + 1);
      sequence = sequence.substr(sequence.find_last_of('\n') + 1);
      std::printf("# %d beams: %s (cosmo_simulate %.0f s wall, %.0f s CPU%s)\n", beams, sequence.c_str(),
                  simulated.wall_s, simulated.cpu_s,
                  simulated.output.find("cache hit") != std::string::npos ? ", cached" : "");
      std::fflush(stdout);
      const fs::path cache = dir / ("scan_cache_" + std::to_string(beams));
      fs::remove_all(cache);
      fs::path first_jrl;
      for (const std::string& run : runs) {
        if (run != "off" && run != "first" && run != "warm") throw std::runtime_error("unknown run '" + run + "'");
        const fs::path out = dir / ("out_" + std::to_string(beams) + "_" + run);
        fs::remove_all(out);
        if (run == "first") fs::remove_all(cache);
        const std::string env = "COSMO_SCAN_CACHE=" + (run == "off" ? std::string("off") : cache.string());
        const std::string load = loadAverage();
        const Run r =
            runProgram({(bin / "cosmo_generate").string(), sequence, "--out", out.string(), "--comm", comm, "--quiet"},
                       {env}, dir / ("generate_" + std::to_string(beams) + "_" + run + ".log"));
        if (r.status != 0) throw std::runtime_error("cosmo_generate failed (" + run + "):\n" + r.output);
        std::smatch m;
        if (!std::regex_search(r.output, m, std::regex(R"(trials, ([0-9.]+) s, noise models)")))
          throw std::runtime_error("cannot find the sequence duration in cosmo_generate's output");
        const double seconds = std::stod(m[1]);
        const fs::path jrl = out / (name + "_" + comm + ".jrl");
        std::string same = "-";
        if (first_jrl.empty())
          first_jrl = jrl;
        else
          same = sameBytes(first_jrl, jrl) ? "identical" : "DIFFERENT";
        std::printf("%-6d %-6s %9.1f %9.1f %9.2f %11.2f %9.0f %6s  %s (%.1f s of sequence)\n", beams, run.c_str(),
                    r.wall_s, r.cpu_s, seconds / r.wall_s, r.cpu_s / seconds, directoryMb(cache), load.c_str(),
                    same.c_str(), seconds);
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_sequence_speed: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
