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
#include <set>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/comm/radio_params.hpp"
#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/keyframe_taker.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/sim/simulation_params.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

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

}  // namespace

int main(int argc, char** argv) {
  keepScanBuffersInProcess();
  std::string sim_config = defaultConfigDir() + "/sim/default.yaml", lidar, comm = "wifi";
  double length = 0.0;
  unsigned threads = 0;
  bool spill = true;
  std::size_t report_every = 100, target_keyframes = 4500, target_robots = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto val = [&]() { return std::string(i + 1 < argc ? argv[++i] : ""); };
    if (a == "--sim")
      sim_config = val();
    else if (a == "--lidar")
      lidar = val();
    else if (a == "--length")
      length = std::stod(val());
    else if (a == "--comm")
      comm = val();
    else if (a == "--registration-threads")
      threads = static_cast<unsigned>(std::stoul(val()));
    else if (a == "--report-every")
      report_every = std::stoul(val());
    else if (a == "--target-keyframes")
      target_keyframes = std::stoul(val());
    else if (a == "--target-robots")
      target_robots = std::stoul(val());
    else if (a == "--no-spill")
      spill = false;
    else {
      std::cerr
          << "usage: bench_keyframe_memory [--sim FILE] [--lidar os1_64|os1_128] [--length M] [--comm wifi|proradio]\n"
             "         [--registration-threads N] [--report-every K] [--target-keyframes N] [--target-robots R]\n"
             "         [--no-spill]\n";
      return 2;
    }
  }
  try {
    sim::SimulationParams sp = sim::SimulationParams::load(sim_config);
    if (!lidar.empty()) sp.lidar = sim::LidarModel::byName(lidar);
    if (length > 0.0)
      for (auto& t : sp.trials) {
        t.route.waypoints.clear();
        t.length = length;
        t.route.length = length;
      }
    const std::string config_dir = defaultConfigDir();
    TeamRunParams params;
    params.frontend = FrontendParams::loadDir(config_dir);
    params.frontend.spill_keyframes = spill;
    params.radio = RadioParams::fromConfig(ConfigNode::load(config_dir + "/comm/" + comm + ".yaml"));
    params.noise = NoiseModels::load(config_dir + "/noise_models/synthetic.yaml");
    params.registration_threads = threads;

    bench::Stopwatch total;
    const sim::PlannedSequence seq = sim::planSequence(sp);
    std::vector<Trial> trials;
    std::map<char, Trajectory> references;
    std::vector<Event> events;
    StampNs start = 0;
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
      references[t.robot] = t.sensor;
      for (std::size_t k = 0; k < t.stamps.size(); ++k) events.push_back({t.stamps[k], t.robot, k});
      std::printf("robot %c: %.0f m, %zu scans (%s, %d beams)\n", t.robot, t.body.length(), t.stamps.size(),
                  sp.lidar.name.c_str(), sp.lidar.beams);
      trials.push_back(std::move(t));
    }
    std::sort(events.begin(), events.end());
    start = events.front().stamp;
    const StampNs origin = radioGridOrigin(start, params.radio.step);
    TeamRun run(sp.name + "_memory", references, params, 1, origin);
    std::map<char, KeyframeTaker> takers;
    std::map<char, std::unique_ptr<sim::ScanSimulator>> simulators;
    std::map<char, const Trial*> by_robot;
    for (const Trial& t : trials) {
      takers.emplace(t.robot, KeyframeTaker(params.frontend));
      simulators[t.robot] = std::make_unique<sim::ScanSimulator>(*t.world, sp.lidar);
      by_robot[t.robot] = &t;
    }

    struct Report {
      std::size_t keyframes, rss, hwm;
    };
    std::vector<Report> reports;
    const auto report = [&](bool last) {
      if (last) run.drain();
      const std::size_t kfs = run.counts().keyframes;
      Report r{kfs, statusBytes("VmRSS"), statusBytes("VmHWM")};
      reports.push_back(r);
      std::set<const void*> seen;
      FrontendFootprint team;
      for (char robot : run.robots()) team += run.frontend(robot).footprint(seen);
      const FeatureCacheFootprint fc = run.frontend(run.robots().front()).featureCache().footprint();
      std::printf(
          "keyframes %5zu  RSS %7.1f MB  peak %7.1f MB | scans own %zu + received %zu: %7.1f MB in memory, "
          "%7.1f MB spilled | features %zu: %7.1f MB in memory, %7.1f MB spilled | descriptors %6.1f MB | "
          "LC %zu+%zu (%.0f s)\n",
          kfs, mb(r.rss), mb(r.hwm), team.own_scans, team.teammate_scans, mb(team.scan_bytes_in_memory),
          mb(team.scan_bytes_spilled), fc.entries, mb(fc.bytes_in_memory), mb(fc.bytes_spilled),
          mb(team.descriptor_bytes), run.counts().intra_accepted, run.counts().inter_accepted,
          total.elapsedMs() * 1e-3);
      std::fflush(stdout);
    };

    std::size_t next_report = report_every;
    for (const Event& e : events) {
      const Trial& t = *by_robot.at(e.robot);
      OdometryResult odo;
      odo.pose = t.sensor.atClamped(e.stamp);  // perfect odometry
      odo.initial_guess = "reference";
      KeyframeTaker& taker = takers.at(e.robot);
      std::shared_ptr<const Scan> kf_scan;
      if (taker.update(e.stamp, odo.pose).is_keyframe) {
        const Scan sweep = simulators.at(e.robot)->simulate(t.body, t.extrinsic, e.stamp - t.shift, t.noise_seed);
        Scan shifted = sweep;
        shifted.stamp = e.stamp;
        kf_scan = std::make_shared<const Scan>(taker.keyframeScan(shifted, t.sensor));
      }
      run.addPrepared(e.robot, e.stamp, odo, std::move(kf_scan));
      if (run.counts().keyframes >= next_report) {
        report(false);
        next_report += report_every;
      }
    }
    run.finish(events.back().stamp);
    report(true);

    const Report& a = reports.front();
    const Report& b = reports.back();
    const double slope = b.keyframes > a.keyframes ? (static_cast<double>(b.hwm) - static_cast<double>(a.hwm)) /
                                                         static_cast<double>(b.keyframes - a.keyframes)
                                                   : 0.0;
    const double base = static_cast<double>(a.hwm) - slope * static_cast<double>(a.keyframes);
    std::printf("\n%s, %d beams, %zu robots, %s: %zu keyframes, peak RSS %.1f MB (%.1f s)\n", sp.name.c_str(),
                sp.lidar.beams, trials.size(), comm.c_str(), b.keyframes, mb(b.hwm), total.elapsedMs() * 1e-3);
    std::printf("peak RSS slope %.1f kB per keyframe (keyframes %zu -> %zu), intercept %.1f MB\n", slope / 1e3,
                a.keyframes, b.keyframes, mb(base));
    // What a keyframe costs grows with the teammates that receive it (their descriptors, their copies without
    // spilling): the robot-scaled figure assumes the whole slope does, an upper bound.
    const double robot_scale =
        trials.size() > 1 ? static_cast<double>(target_robots - 1) / static_cast<double>(trials.size() - 1) : 1.0;
    std::printf(
        "extrapolated peak for %zu keyframes: %.2f GB; with %zu robots instead of %zu (slope x %.2f): %.2f GB\n",
        target_keyframes, (base + slope * static_cast<double>(target_keyframes)) / 1e9, target_robots, trials.size(),
        robot_scale, (base + slope * robot_scale * static_cast<double>(target_keyframes)) / 1e9);
  } catch (const std::exception& e) {
    std::cerr << "bench_keyframe_memory: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
