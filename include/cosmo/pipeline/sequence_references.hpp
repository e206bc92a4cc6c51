#pragma once
// A trial's reference trajectory in the form the pipeline uses: LiDAR (sensor) poses in the world frame,
// T_world_lidar = T_world_body * T_body_lidar (the trial's extrinsic), in sequence time.
#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

namespace cosmo::pipeline {

/// Body poses in recorded time as LiDAR poses in sequence time (trials::loadSensorReference reads a trial's
/// reference file and calls this).
Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing);

}  // namespace cosmo::pipeline
