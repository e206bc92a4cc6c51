#pragma once
// A trial's reference trajectory in the form the pipeline uses: LiDAR (sensor) poses in the world frame,
// T_world_lidar = T_world_body * T_body_lidar (the trial's extrinsic), in sequence time, with the sequence's one
// reference offset subtracted from every position (config `reference_offset`: trials that share a frame, e.g. the
// four CU-Multi robots of a site in UTM, keep sharing it near the origin). trials/trial_reference.hpp reads the
// files and calls this.
#include <Eigen/Core>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::sequence {

/// Body poses (recorded time) to sensor poses in sequence time, `offset` subtracted from the positions.
Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing,
                             const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());

/// The offset of `reference_offset: anchor`: the anchor's first reference position rounded to whole metres.
Eigen::Vector3d roundedFirstPosition(const Trajectory& anchor_reference);

}  // namespace cosmo::sequence
