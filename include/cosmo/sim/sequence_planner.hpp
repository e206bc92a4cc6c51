#pragma once
// A whole synthetic sequence before any ray is cast: the world, each trial's route and body trajectory,
// and the stamps of its scans. Scans are then made one by one with ScanSimulator (see scanSeed()).
#include <memory>
#include <string>
#include <vector>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/sim/simulation_params.hpp"
#include "cosmo/sim/world.hpp"

namespace cosmo::sim {

struct PlannedTrial {
  TrialParams params;
  std::vector<int> route;              ///< network nodes
  Trajectory body;                     ///< reference trajectory (body in world), params.motion.rate_hz
  std::vector<StampNs> scan_stamps;    ///< sweep-end stamps; every sweep lies inside the trajectory
  std::uint64_t noise_seed = 0;        ///< LiDAR noise seed of this trial (and its sensor's calibration)
  std::shared_ptr<const World> world;  ///< what this trial's LiDAR sees: the world with that day's clutter
};

struct PlannedSequence {
  std::shared_ptr<const World> world;  ///< the world as generated (routes, terrain; every trial's fixed objects)
  std::vector<PlannedTrial> trials;
};

/// Deterministic in params (world, routes, trajectories, seeds).
PlannedSequence planSequence(const SimulationParams& params);

/// Seed derived from a parent seed and a label (stable across platforms).
std::uint64_t deriveSeed(std::uint64_t seed, const std::string& label);

/// Writes the sequence config (config/sequence_format.md) listing the trials with relative file names
/// <trial>.bag and <trial>_pose_inW.csv.
void writeSequenceConfig(const std::string& path, const SimulationParams& params);

}  // namespace cosmo::sim
