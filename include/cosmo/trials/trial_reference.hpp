#pragma once
// A trial's reference in the form the pipeline uses: LiDAR poses in the world frame in sequence time,
// T_world_lidar = T_world_body * T_body_lidar (the trial's extrinsic), minus the sequence's reference offset, read
// from whichever reference format the trial's `reference:` file has (reference_file.hpp). Also which of the
// trial's scans that reference covers (sequence/trial_coverage.hpp) and the sequence's one reference offset.
#include <Eigen/Core>
#include <map>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/sequence/trial_coverage.hpp"

namespace cosmo::trials {

/// The reference file as read: body poses in the file's frame and the trial's recorded time; an empty
/// `reference` path gives an empty trajectory. Throws naming the file and line on bad input.
Trajectory readBodyReference(const sequence::TrialConfig& trial);

/// Which of the trial's scans its reference covers.
sequence::TrialCoverage trialCoverage(const sequence::TrialConfig& trial);

/// The sequence's reference offset: zero (`none`), the configured one, or the anchor trial's first reference
/// position rounded to whole metres (`anchor`; zero when the anchor has no reference).
Eigen::Vector3d sequenceReferenceOffset(const sequence::SequenceConfig& config);

/// An empty `reference` path gives an empty trajectory. Throws naming the file and line on bad input.
Trajectory loadSensorReference(const sequence::TrialConfig& trial, const sequence::TrialTiming& timing,
                               const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());

/// Every trial's sensor reference (robot -> trajectory), with the sequence's offset.
std::map<char, Trajectory> loadSequenceReferences(const sequence::SequenceConfig& config,
                                                  const sequence::SequenceTiming& timing);

}  // namespace cosmo::trials
