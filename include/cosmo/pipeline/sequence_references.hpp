#pragma once
// A trial's reference trajectory in the form the pipeline uses: LiDAR (sensor) poses in the world frame,
// T_world_lidar = T_world_body * T_body_lidar (the trial's extrinsic), in sequence time.
#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

namespace cosmo::pipeline {

/// Reads the trial's reference CSV (MCD pose_inW.csv: num, sec, x, y, z, qx, qy, qz, qw); an empty
/// `reference` path gives an empty trajectory. Throws naming the file on bad input.
Trajectory loadSensorReference(const TrialConfig& trial, const TrialTiming& timing);

/// The same for trajectories already read (body poses in recorded time).
Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing);

}  // namespace cosmo::pipeline
