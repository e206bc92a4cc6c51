#pragma once
// A trial's reference trajectory in the form the pipeline uses: LiDAR (sensor) poses in the world frame,
// T_world_lidar = T_world_body * T_body_lidar (the trial's extrinsic), in sequence time, with the sequence's one
// reference offset subtracted from every position (config `reference_offset`: trials that share a frame, e.g. the
// four CU-Multi robots of a site in UTM, keep sharing it near the origin).
#include <Eigen/Core>
#include <map>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"
#include "cosmo/pipeline/trial_coverage.hpp"

namespace cosmo::pipeline {

/// The trial's reference file as read: body poses in the file's frame and the trial's recorded time; an empty
/// `reference` path gives an empty trajectory. Throws naming the file on bad input.
Trajectory readBodyReference(const TrialConfig& trial);

/// Which of the trial's scans its reference covers (trial_coverage.hpp).
TrialCoverage trialCoverage(const TrialConfig& trial);

/// The sequence's reference offset: zero (`none`), the configured one, or the anchor trial's first reference
/// position rounded to whole metres (`anchor`; zero when the anchor has no reference).
Eigen::Vector3d sequenceReferenceOffset(const SequenceConfig& config);

/// Reads the trial's reference and converts it (below); an empty `reference` path gives an empty trajectory.
Trajectory loadSensorReference(const TrialConfig& trial, const TrialTiming& timing,
                               const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());

/// Every trial's sensor reference (robot -> trajectory), with the sequence's offset.
std::map<char, Trajectory> loadSequenceReferences(const SequenceConfig& config, const SequenceTiming& timing);

/// Body poses (recorded time) to sensor poses in sequence time, `offset` subtracted from the positions.
Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing,
                             const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());

}  // namespace cosmo::pipeline
