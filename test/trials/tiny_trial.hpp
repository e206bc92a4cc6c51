#pragma once
// The one-trial plan the layout tests simulate: a handheld walk of 30 m around a single block, seen by a small
// LiDAR (`beams` x `columns` at `rate_hz`) so that writing and reading a whole trial takes a fraction of a second.
#include "cosmo/sim/lidar_model.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/sim/simulation_params.hpp"

namespace cosmo::test {

inline sim::LidarModel smallLidar(int beams, int columns, double rate_hz) {
  sim::LidarModel m = sim::LidarModel::os1_64();
  m.beams = beams;
  m.columns = columns;
  m.rate_hz = rate_hz;
  return m;
}

inline sim::PlannedSequence tinyPlan(const sim::LidarModel& lidar) {
  sim::SimulationParams p;
  p.world.blocks_x = 1;
  p.world.blocks_y = 1;
  p.world.outer_ring = 30;
  p.world.terrain_margin = 40;
  p.lidar = lidar;
  sim::TrialParams t;
  t.name = "walk_a";
  t.motion = sim::MotionParams::preset("handheld");
  t.platform = "handheld";
  t.length = 30;
  t.start_node = 0;
  t.route.return_fraction = 1.0;
  p.trials.push_back(t);
  return sim::planSequence(p);
}

}  // namespace cosmo::test
