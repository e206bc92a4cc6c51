#pragma once
// A tiny synthetic team for the pipeline tests, simulated in memory (no bags): the CI campus of
// config/sim/ci.yaml with a lighter LiDAR and short routes. Deterministic in its parameters.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/sim/simulation_params.hpp"

namespace cosmo::test {

struct SyntheticTrial {
  char robot = 'a';
  std::vector<Scan> scans;  ///< recorded time, sensor frame
  Trajectory body;          ///< body in world, recorded time
  Pose3 extrinsic = Pose3::Identity();
};

/// The one trial of `params` (robot a) planned and ray-cast: its scans, body trajectory and extrinsic.
inline SyntheticTrial simulateSingleTrial(const sim::SimulationParams& params) {
  const auto seq = sim::planSequence(params);
  const auto& planned = seq.trials.front();
  const sim::ScanSimulator simulator(*planned.world, params.lidar);
  SyntheticTrial out;
  out.robot = 'a';
  out.body = planned.body;
  out.extrinsic = planned.params.extrinsicPose();
  for (const StampNs stamp : planned.scan_stamps)
    out.scans.push_back(simulator.simulate(planned.body, out.extrinsic, stamp, planned.noise_seed));
  return out;
}

/// `robots` trials starting at junction `start_node` (so they see the same place), each cut to its first
/// `max_scans` scans; a light 32 x 512 LiDAR keeps the tests fast.
inline std::vector<SyntheticTrial> makeSyntheticTeam(int robots, std::size_t max_scans, int start_node = 0) {
  const std::vector<double> lengths(static_cast<std::size_t>(robots), 100.0);
  const double return_fraction = 1.0;
  sim::SimulationParams params = sim::SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/ci.yaml");
  params.lidar = sim::LidarModel::os1_32();
  params.lidar.columns = 512;
  params.trials.clear();
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    sim::TrialParams t;
    t.robot = std::string(1, static_cast<char>('a' + i));
    t.name = "test_" + t.robot;
    t.platform = "atv";
    t.length = lengths[i];
    t.start_node = start_node;
    t.route.length = lengths[i];
    t.route.start_node = start_node;
    t.route.return_fraction = return_fraction;
    t.motion.start_still = 0.5;
    t.motion.end_still = 0.5;
    params.trials.push_back(t);
  }
  const auto seq = sim::planSequence(params);
  std::vector<SyntheticTrial> out;
  for (const auto& t : seq.trials) {
    const sim::ScanSimulator simulator(*t.world, params.lidar);
    SyntheticTrial s;
    s.robot = t.params.robot[0];
    s.body = t.body;
    s.extrinsic = t.params.extrinsicPose();
    for (std::size_t k = 0; k < t.scan_stamps.size() && k < max_scans; ++k)
      s.scans.push_back(simulator.simulate(t.body, s.extrinsic, t.scan_stamps[k], t.noise_seed));
    out.push_back(std::move(s));
  }
  return out;
}

/// makeSyntheticTeam(robots, max_scans), made once per process and argument pair (the tests of a binary share it).
inline const std::vector<SyntheticTrial>& sharedSyntheticTeam(int robots, std::size_t max_scans) {
  static std::map<std::pair<int, std::size_t>, std::vector<SyntheticTrial>> teams;
  auto it = teams.find({robots, max_scans});
  if (it == teams.end())
    it = teams.emplace(std::make_pair(robots, max_scans), makeSyntheticTeam(robots, max_scans)).first;
  return it->second;
}

}  // namespace cosmo::test
