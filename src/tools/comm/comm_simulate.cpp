// comm_simulate: run the radio model offline on reference trajectories and write the per-transfer log.
//
//   comm_simulate [--comm wifi|proradio|<file.yaml>] [--seed N] [--kf-distance 2.0] [--scan-points 65536]
//                 [--size-model paper|real] [--timeout-mode no_progress|total_duration] [--tail 0]
//                 [--trace TRACE.csv] [--write-trace TRACE.csv]
//                 --out transfers.csv  a=<traj> b=<traj>[@offset_s] ...
//
// <traj>: a TUM file (stamp x y z qx qy qz qw) or an MCD pose_inW.csv (by the .csv extension). @offset_s
// shifts a robot's trajectory in time (spec section 3). A keyframe is offered every --kf-distance metres of
// travel along the reference (a stand-in for the front-end's odometry keyframes) with S = 12 * --scan-points
// bytes (with --size-model real the payload is S * 0.653, there being no scan to compress). Robots are off
// before their first pose and stay on at their last pose until the latest end (+ --tail seconds).
// Radio time 0 (and a trace's time 0) is the earliest trajectory start rounded down to the step grid.
// --trace replays a radio trace (comm/radio_trace.hpp) inside its windows, --comm's phi(d) outside them;
// --write-trace writes the run's own connectivity samples as a trace, which replayed with the same seed and
// trajectories gives the same transfers.
// Writes the CSV (comm/transfer_log.hpp), <out>.summary.json and the run's connectivity per robot pair
// (<out without .csv>_connectivity.json, comm/connectivity.hpp); prints the summary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <optional>
#include <string>

#include <fstream>

#include "cosmo/comm/comm_model.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/pose_io.hpp"

using namespace cosmo;

namespace {
struct Options {
  std::string comm = "wifi", out, size_model, timeout_mode, trace, write_trace;
  std::uint64_t seed = 0;
  double kf_distance = 2.0, tail = 0.0;
  std::size_t scan_points = 65536;
  std::vector<std::string> robots;  ///< r=<traj>[@offset_s]
  std::map<char, Trajectory> trajectories;
};

/// A robot's argument r=<traj>[@offset_s]: its trajectory, shifted by the offset.
Trajectory readRobotTrajectory(const std::string& arg) {
  std::string path = arg.substr(2);
  double offset = 0.0;
  const auto at = path.rfind('@');
  if (at != std::string::npos) {
    offset = std::stod(path.substr(at + 1));
    path = path.substr(0, at);
  }
  const bool csv = path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
  Trajectory t = csv ? readMcdPoseCsv(path) : readTumTrajectory(path);
  if (t.empty()) throw std::invalid_argument(path + ": empty trajectory");
  return t.shifted(static_cast<long long>(offset * 1e9));
}

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  CommandLine app(
      "comm_simulate",
      "Runs the radio model offline on reference trajectories and writes the per-transfer log (CSV and "
      "<out>.summary.json) and the connectivity per robot pair (<out>_connectivity.json); prints the summary.");
  app.add_option("--comm", o.comm, "wifi, proradio or a comm config (YAML)")->capture_default_str();
  app.add_option("--seed", o.seed, "the radio's seed")->capture_default_str();
  app.add_option("--kf-distance", o.kf_distance,
                 "a keyframe is offered every this many metres of travel along the reference")
      ->capture_default_str()
      ->check(Positive);
  app.add_option("--scan-points", o.scan_points, "points per scan: S = 12 * n bytes")->capture_default_str();
  app.add_option("--size-model", o.size_model, "paper or real (the payload is S * 0.653, there being no scan)");
  app.add_option("--timeout-mode", o.timeout_mode, "no_progress or total_duration");
  app.add_option("--tail", o.tail, "seconds every robot stays on after the latest end")->capture_default_str();
  app.add_option("--trace", o.trace, "a radio trace (CSV) replayed inside its windows, --comm's phi(d) outside them")
      ->type_name("TRACE.csv");
  app.add_option("--write-trace", o.write_trace, "writes the run's own connectivity samples as a trace")
      ->type_name("TRACE.csv");
  app.add_option("--out", o.out, "the transfer log (CSV)")->required();
  app.add_option("ROBOT=TRAJ", o.robots,
                 "a robot's trajectory, r=<traj>[@offset_s]: a TUM file or an MCD pose_inW.csv (by the .csv "
                 "extension); @offset_s shifts it in time")
      ->required();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return exit_code;
  for (const std::string& r : o.robots) {
    if (r.size() < 3 || r[1] != '=') {
      std::fprintf(stderr, "comm_simulate: unknown argument '%s'\n", r.c_str());
      return 2;
    }
    o.trajectories[r[0]] = readRobotTrajectory(r);
  }
  return std::nullopt;
}

comm::RadioParams radioParams(const Options& o) {
  comm::RadioParams params = comm::resolveCommModel(o.comm, "").params;
  if (!o.size_model.empty()) params.size_model = comm::sizeModelFromString(o.size_model, "--size-model");
  if (!o.timeout_mode.empty()) params.timeout_mode = comm::timeoutModeFromString(o.timeout_mode, "--timeout-mode");
  if (!o.trace.empty()) params.trace = std::make_shared<const comm::RadioTrace>(comm::RadioTrace::read(o.trace));
  return params;
}

/// Every step from the earliest start to the latest end (+ tail): robots on from their first pose, a keyframe
/// offered at the first pose and every kf_distance of travel.
void simulate(const Options& o, comm::RadioSimulator& sim) {
  StampNs t0 = ~StampNs{0}, t1 = 0;
  for (const auto& [r, t] : o.trajectories) {
    t0 = std::min(t0, t.startStamp());
    t1 = std::max(t1, t.endStamp());
  }
  const StampNs step_ns = toStampNs(sim.params().step);
  const StampNs origin = (t0 / step_ns) * step_ns;
  sim.setTimeOrigin(origin);
  const double end = toSeconds(t1 - origin) + o.tail;
  std::map<char, Eigen::Vector3d> last_pos;
  std::map<char, double> travelled;
  std::map<char, std::size_t> next_kf;
  const std::size_t raw = 12 * o.scan_points;
  const std::size_t real = static_cast<std::size_t>(0.653 * raw);
  for (double t = sim.nextStepTime(); t <= end + 1e-9; t = sim.nextStepTime()) {
    const StampNs stamp = origin + static_cast<StampNs>(std::llround(t * 1e9));
    for (const auto& [r, traj] : o.trajectories) {
      if (stamp < traj.startStamp()) continue;  // off before its first measurement
      const Eigen::Vector3d p = traj.atClamped(stamp).translation();
      sim.setRobotState(r, p, true);
      if (!last_pos.count(r)) {
        last_pos[r] = p;
        sim.offerKeyframe(r, next_kf[r]++, real, raw);
      } else if (stamp <= traj.endStamp()) {
        travelled[r] += (p - last_pos[r]).norm();
        last_pos[r] = p;
        if (travelled[r] > o.kf_distance) {
          travelled[r] = 0.0;
          sim.offerKeyframe(r, next_kf[r]++, real, raw);
        }
      }
    }
    sim.step(t);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options o;
    if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
    std::vector<char> ids;
    for (const auto& [r, t] : o.trajectories) ids.push_back(r);
    comm::RadioSimulator sim(radioParams(o), ids, o.seed);
    sim.recordLinks(!o.write_trace.empty());
    simulate(o, sim);
    writeTransferLog(o.out, sim);
    if (!o.write_trace.empty()) {
      std::ofstream out(o.write_trace);
      comm::RadioTrace::fromRecords(sim.linkRecords(), sim.params().step).write(out);
      if (!out.flush()) throw std::runtime_error(o.write_trace + ": cannot write");
    }
    std::cout << transferSummary(sim).dump() << "\n";
  } catch (const std::exception& e) {
    std::fprintf(stderr, "comm_simulate: %s\n", e.what());
    return 1;
  }
  return 0;
}
