#pragma once
// A trial's reference in the form the pipeline uses: LiDAR poses in the world frame in sequence time,
// T_world_lidar = T_world_body * T_body_lidar (the trial's extrinsic), read from whichever reference format the
// trial's `reference:` file has (reference_file.hpp).
#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

namespace cosmo::trials {

/// An empty `reference` path gives an empty trajectory. Throws naming the file and line on bad input.
Trajectory loadSensorReference(const pipeline::TrialConfig& trial, const pipeline::TrialTiming& timing);

}  // namespace cosmo::trials
