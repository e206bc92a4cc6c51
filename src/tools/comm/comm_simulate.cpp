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
// Writes the CSV (comm/transfer_log.hpp) and <out>.summary.json; prints the summary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <string>

#include <fstream>

#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/common/pose_io.hpp"

using namespace cosmo;

namespace {
constexpr const char* kUsage =
    "usage: comm_simulate [--comm wifi|proradio|file.yaml] [--seed N] [--kf-distance m] [--scan-points n] "
    "[--size-model paper|real] [--timeout-mode no_progress|total_duration] [--tail s] [--trace TRACE.csv] "
    "[--write-trace TRACE.csv] --out transfers.csv a=traj[@offset_s] b=traj ...\n";

int usage(const char* msg) {
  std::fprintf(stderr, "comm_simulate: %s\n%s", msg, kUsage);
  return 2;
}
struct Options {
  std::string comm = "wifi", out, size_model, timeout_mode, trace, write_trace;
  std::uint64_t seed = 0;
  double kf_distance = 2.0, tail = 0.0;
  std::size_t scan_points = 65536;
  std::map<char, Trajectory> trajectories;
  bool help = false;
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

/// Throws std::invalid_argument on a missing value; returns an error message for anything else wrong ("" if none).
std::string parseArgs(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
      return "";
    }
    if (a == "--comm")
      o.comm = next();
    else if (a == "--seed")
      o.seed = std::stoull(next());
    else if (a == "--kf-distance")
      o.kf_distance = std::stod(next());
    else if (a == "--scan-points")
      o.scan_points = std::stoul(next());
    else if (a == "--size-model")
      o.size_model = next();
    else if (a == "--timeout-mode")
      o.timeout_mode = next();
    else if (a == "--tail")
      o.tail = std::stod(next());
    else if (a == "--out")
      o.out = next();
    else if (a == "--trace")
      o.trace = next();
    else if (a == "--write-trace")
      o.write_trace = next();
    else if (a.size() > 2 && a[1] == '=')
      o.trajectories[a[0]] = readRobotTrajectory(a);
    else
      return "unknown argument '" + a + "'";
  }
  if (o.out.empty()) return "--out is required";
  if (o.trajectories.empty()) return "no robot trajectories given";
  if (!(o.kf_distance > 0)) return "--kf-distance must be > 0";
  return "";
}

RadioParams radioParams(const Options& o) {
  RadioParams params = (o.comm.size() > 5 && o.comm.compare(o.comm.size() - 5, 5, ".yaml") == 0)
                           ? RadioParams::fromConfig(ConfigNode::load(o.comm))
                           : RadioParams::byName(o.comm);
  if (!o.size_model.empty()) params.size_model = sizeModelFromString(o.size_model, "--size-model");
  if (!o.timeout_mode.empty()) params.timeout_mode = timeoutModeFromString(o.timeout_mode, "--timeout-mode");
  if (!o.trace.empty()) params.trace = std::make_shared<const RadioTrace>(RadioTrace::read(o.trace));
  return params;
}

/// Every step from the earliest start to the latest end (+ tail): robots on from their first pose, a keyframe
/// offered at the first pose and every kf_distance of travel.
void simulate(const Options& o, RadioSimulator& sim) {
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
    const std::string error = parseArgs(argc, argv, o);
    if (o.help) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (!error.empty()) return usage(error.c_str());
    std::vector<char> ids;
    for (const auto& [r, t] : o.trajectories) ids.push_back(r);
    RadioSimulator sim(radioParams(o), ids, o.seed);
    sim.recordLinks(!o.write_trace.empty());
    simulate(o, sim);
    writeTransferLog(o.out, sim);
    if (!o.write_trace.empty()) {
      std::ofstream out(o.write_trace);
      RadioTrace::fromRecords(sim.linkRecords(), sim.params().step).write(out);
      if (!out.flush()) throw std::runtime_error(o.write_trace + ": cannot write");
    }
    std::cout << transferSummary(sim).dump() << "\n";
  } catch (const std::exception& e) {
    std::fprintf(stderr, "comm_simulate: %s\n", e.what());
    return 1;
  }
  return 0;
}
