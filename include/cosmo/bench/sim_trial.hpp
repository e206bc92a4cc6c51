#pragma once
// What the trial-container benchmarks share: one simulated 200 m ATV trial in a 2 x 2-block campus with a
// given LiDAR, and the process's CPU time (benchmark programs only: the core never reads a clock).
#include <ctime>

#include "cosmo/sim/sequence_planner.hpp"

namespace cosmo::bench {

/// CPU time of the whole process so far, ms.
inline double processCpuMs() { return 1e3 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// An Ouster OS1 with `beams` beams (the OS1-128's optics for 128, the OS1-64's otherwise).
inline sim::LidarModel benchOuster(int beams) {
  sim::LidarModel lidar = beams == 128 ? sim::LidarModel::os1_128() : sim::LidarModel::os1_64();
  lidar.beams = beams;
  return lidar;
}

/// The planned sequence of that one trial ("bench").
inline sim::PlannedSequence benchTrialPlan(const sim::LidarModel& lidar) {
  sim::SimulationParams p;
  p.world.blocks_x = 2;
  p.world.blocks_y = 2;
  p.lidar = lidar;
  sim::TrialParams t;
  t.name = "bench";
  t.motion = sim::MotionParams::preset("atv");
  t.length = 200;
  t.start_node = 0;
  p.trials.push_back(t);
  return sim::planSequence(p);
}

}  // namespace cosmo::bench
