// bench_keyframe_memory: the memory a long run keeps per keyframe, and what holds it.
//
//   bench_keyframe_memory [--sim config/sim/default.yaml] [--lidar os1_64|os1_128] [--length M] [--comm wifi]
//                         [--registration-threads N] [--report-every K] [--target-keyframes 4500]
//                         [--target-robots 5] [--no-spill]
//
// A synthetic sequence (cosmo_simulate's planner, every trial started at the same time) goes through TeamRun, the
// offline driver's team (radio, place recognition, loop-closure registrations, recorder) with the reference poses as
// odometry; only the keyframe scans are ray cast (the keyframer decides on the poses, as OdometryRunAhead does), so a
// long run costs the front-end's work, not the simulation of every sweep. --length M gives every trial a seeded
// random route of M metres instead of the config's waypoints. Every K keyframes it prints the team's keyframes, the
// process's resident and peak memory (/proc/self/status) and what the team's stores hold (FrontendFootprint,
// FeatureCache, keyframe spill); at the end the slope of the peak between the first report and the last (bytes per
// keyframe) and the extrapolation to --target-keyframes keyframes in all (ntu_r5_00: 8.9 km at 2 m, 5 robots).
// --no-spill keeps every kept scan and feature in memory (FrontendParams::spill_keyframes = false), for comparison.
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/comm/radio_params.hpp"
#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/frontend/keyframe_taker.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/sim/simulation_params.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;
using namespace cosmo::sequence;

namespace {

/// VmRSS / VmHWM of this process (bytes).
std::size_t statusBytes(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) return std::stoull(line.substr(key.size() + 1)) * 1024;
  return 0;
}

double mb(double bytes) { return bytes / 1e6; }

struct Trial {
  char robot = 'a';
  Trajectory sensor;  ///< sensor poses in the world, sequence time
  Trajectory body;
  Pose3 extrinsic;
  std::vector<StampNs> stamps;  ///< sequence time
  std::uint64_t noise_seed = 0;
  std::shared_ptr<const sim::World> world;
  StampNs shift = 0;  ///< sequence time - planned time
};

struct Event {
  StampNs stamp;
  char robot;
  std::size_t k;
  bool operator<(const Event& o) const { return stamp != o.stamp ? stamp < o.stamp : robot < o.robot; }
};

struct Options {
  std::string sim_config = defaultConfigDir() + "/sim/default.yaml", lidar, comm = "wifi";
  double length = 0.0;
  unsigned threads = 0;
  bool spill = true;
  std::size_t report_every = 100, target_keyframes = 4500, target_robots = 5;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  cosmo::CommandLine app("bench_keyframe_memory",
                         "The memory a long run keeps per keyframe, and what holds it: a synthetic sequence through "
                         "TeamRun with the reference poses as odometry, only the keyframe scans ray cast.");
  app.add_option("--sim", o.sim_config, "the simulation config")->type_name("FILE")->capture_default_str();
  app.add_option("--lidar", o.lidar, "os1_64 or os1_128 (default: the config's)");
  app.add_option("--length", o.length, "every trial a seeded random route of M metres instead of the waypoints")
      ->type_name("M");
  app.add_option("--comm", o.comm, "wifi or proradio")->capture_default_str();
  app.add_option("--registration-threads", o.threads, "threads of the loop-closure registrations")
      ->capture_default_str();
  app.add_option("--report-every", o.report_every, "a memory line every K keyframes")->capture_default_str();
  app.add_option("--target-keyframes", o.target_keyframes, "the extrapolation's keyframes in all")
      ->capture_default_str();
  app.add_option("--target-robots", o.target_robots, "the extrapolation's robots")->capture_default_str();
  bool no_spill = false;
  app.add_flag("--no-spill", no_spill, "keep every kept scan and feature in memory, for comparison");
  const std::optional<int> exit_code = app.parseOrExit(argc, argv);
  o.spill = !no_spill;
  return exit_code;
}

sim::SimulationParams simulationParams(const Options& o) {
  sim::SimulationParams sp = sim::SimulationParams::load(o.sim_config);
  if (!o.lidar.empty()) sp.lidar = sim::LidarModel::byName(o.lidar);
  if (o.length > 0.0)
    for (auto& t : sp.trials) {
      t.route.waypoints.clear();
      t.length = o.length;
      t.route.length = o.length;
    }
  return sp;
}

TeamRunParams teamParams(const Options& o) {
  const std::string config_dir = defaultConfigDir();
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(config_dir);
  params.frontend.spill_keyframes = o.spill;
  params.radio = comm::RadioParams::fromConfig(ConfigNode::load(config_dir + "/comm/" + o.comm + ".yaml"));
  params.noise = dataset::NoiseModels::load(config_dir + "/noise_models/synthetic.yaml");
  params.registration_threads = o.threads;
  return params;
}

/// The planned trials, every one started at the sequence start, and their scans in the team's order.
struct Team {
  std::vector<Trial> trials;
  std::map<char, Trajectory> references;
  std::vector<Event> events;
};

Team planTeam(const sim::SimulationParams& sp) {
  Team team;
  const sim::PlannedSequence seq = sim::planSequence(sp);
  for (const auto& pt : seq.trials) {
    Trial t;
    t.robot = pt.params.robot.at(0);
    t.extrinsic = pt.params.extrinsicPose();
    t.shift = static_cast<StampNs>(sp.start_epoch * 1e9) - pt.body.startStamp();  // every trial starts together
    t.body = pt.body.shifted(static_cast<long long>(t.shift));
    std::vector<StampedPose> sensor;
    for (const auto& p : t.body.poses()) sensor.push_back({p.stamp, p.pose * t.extrinsic});
    t.sensor = Trajectory(sensor);
    for (StampNs s : pt.scan_stamps) t.stamps.push_back(s + t.shift);
    t.noise_seed = pt.noise_seed;
    t.world = pt.world;
    team.references[t.robot] = t.sensor;
    for (std::size_t k = 0; k < t.stamps.size(); ++k) team.events.push_back({t.stamps[k], t.robot, k});
    std::printf("robot %c: %.0f m, %zu scans (%s, %d beams)\n", t.robot, t.body.length(), t.stamps.size(),
                sp.lidar.name.c_str(), sp.lidar.beams);
    team.trials.push_back(std::move(t));
  }
  std::sort(team.events.begin(), team.events.end());
  return team;
}

struct Report {
  std::size_t keyframes, rss, hwm;
};

/// One report line: the team's keyframes, the process's memory and what the team's stores hold.
Report report(TeamRun& run, const bench::Stopwatch& total, bool last) {
  if (last) run.drain();
  const std::size_t kfs = run.counts().keyframes;
  Report r{kfs, statusBytes("VmRSS"), statusBytes("VmHWM")};
  std::set<const void*> seen;
  frontend::FrontendFootprint team;
  for (char robot : run.robots()) team += run.frontend(robot).footprint(seen);
  const frontend::FeatureCacheFootprint fc = run.frontend(run.robots().front()).featureCache().footprint();
  std::printf(
      "keyframes %5zu  RSS %7.1f MB  peak %7.1f MB | scans own %zu + received %zu: %7.1f MB in memory, "
      "%7.1f MB spilled | features %zu: %7.1f MB in memory, %7.1f MB spilled | descriptors %6.1f MB | "
      "LC %zu+%zu (%.0f s)\n",
      kfs, mb(r.rss), mb(r.hwm), team.own_scans, team.teammate_scans, mb(team.scan_bytes_in_memory),
      mb(team.scan_bytes_spilled), fc.entries, mb(fc.bytes_in_memory), mb(fc.bytes_spilled), mb(team.descriptor_bytes),
      run.counts().intra_accepted, run.counts().inter_accepted, total.elapsedMs() * 1e-3);
  std::fflush(stdout);
  return r;
}

/// Every scan through the team with perfect odometry; only keyframe scans are ray cast. A report every
/// `report_every` keyframes and at the end.
std::vector<Report> runTeam(const Team& team, const sim::SimulationParams& sp, const TeamRunParams& params,
                            std::size_t report_every, const bench::Stopwatch& total) {
  const StampNs origin = radioGridOrigin(team.events.front().stamp, params.radio.step);
  TeamRun run(sp.name + "_memory", team.references, params, 1, origin);
  std::map<char, frontend::KeyframeTaker> takers;
  std::map<char, std::unique_ptr<sim::ScanSimulator>> simulators;
  std::map<char, const Trial*> by_robot;
  for (const Trial& t : team.trials) {
    takers.emplace(t.robot, frontend::KeyframeTaker(params.frontend));
    simulators[t.robot] = std::make_unique<sim::ScanSimulator>(*t.world, sp.lidar);
    by_robot[t.robot] = &t;
  }
  std::vector<Report> reports;
  std::size_t next_report = report_every;
  for (const Event& e : team.events) {
    const Trial& t = *by_robot.at(e.robot);
    odometry::OdometryResult odo;
    odo.pose = t.sensor.atClamped(e.stamp);  // perfect odometry
    odo.initial_guess = "reference";
    frontend::KeyframeTaker& taker = takers.at(e.robot);
    std::shared_ptr<const Scan> kf_scan;
    if (taker.update(e.stamp, odo.pose).is_keyframe) {
      const Scan sweep = simulators.at(e.robot)->simulate(t.body, t.extrinsic, e.stamp - t.shift, t.noise_seed);
      Scan shifted = sweep;
      shifted.stamp = e.stamp;
      kf_scan = std::make_shared<const Scan>(taker.keyframeScan(shifted, t.sensor));
    }
    run.add(e.robot, frontend::OwnScan::prepared(e.stamp, odo, std::move(kf_scan)));
    if (run.counts().keyframes >= next_report) {
      reports.push_back(report(run, total, false));
      next_report += report_every;
    }
  }
  run.finish(team.events.back().stamp);
  reports.push_back(report(run, total, true));
  return reports;
}

/// The peak's slope per keyframe between the first report and the last, and the extrapolations.
void printSummary(const Options& o, const sim::SimulationParams& sp, std::size_t robots,
                  const std::vector<Report>& reports, const bench::Stopwatch& total) {
  const Report& a = reports.front();
  const Report& b = reports.back();
  const double slope = b.keyframes > a.keyframes ? (static_cast<double>(b.hwm) - static_cast<double>(a.hwm)) /
                                                       static_cast<double>(b.keyframes - a.keyframes)
                                                 : 0.0;
  const double base = static_cast<double>(a.hwm) - slope * static_cast<double>(a.keyframes);
  std::printf("\n%s, %d beams, %zu robots, %s: %zu keyframes, peak RSS %.1f MB (%.1f s)\n", sp.name.c_str(),
              sp.lidar.beams, robots, o.comm.c_str(), b.keyframes, mb(b.hwm), total.elapsedMs() * 1e-3);
  std::printf("peak RSS slope %.1f kB per keyframe (keyframes %zu -> %zu), intercept %.1f MB\n", slope / 1e3,
              a.keyframes, b.keyframes, mb(base));
  // What a keyframe costs grows with the teammates that receive it (their descriptors, their copies without
  // spilling): the robot-scaled figure assumes the whole slope does, an upper bound.
  const double robot_scale =
      robots > 1 ? static_cast<double>(o.target_robots - 1) / static_cast<double>(robots - 1) : 1.0;
  std::printf("extrapolated peak for %zu keyframes: %.2f GB; with %zu robots instead of %zu (slope x %.2f): %.2f GB\n",
              o.target_keyframes, (base + slope * static_cast<double>(o.target_keyframes)) / 1e9, o.target_robots,
              robots, robot_scale, (base + slope * robot_scale * static_cast<double>(o.target_keyframes)) / 1e9);
}

}  // namespace

int main(int argc, char** argv) {
  keepScanBuffersInProcess();
  Options o;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, o)) return *exit_code;
  try {
    const sim::SimulationParams sp = simulationParams(o);
    const TeamRunParams params = teamParams(o);
    bench::Stopwatch total;
    const Team team = planTeam(sp);
    const std::vector<Report> reports = runTeam(team, sp, params, o.report_every, total);
    printSummary(o, sp, team.trials.size(), reports, total);
  } catch (const std::exception& e) {
    std::cerr << "bench_keyframe_memory: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
