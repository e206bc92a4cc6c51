#pragma once
// What a sequence's timing and references are made of, trial by trial: the span of the scans its reference covers
// (sweep-end stamps) and its reference as read, both in the trial's recorded time. The player reads them from the
// trials' bags and reference files, or, when each robot plays its own trial on its own machine (the trial_player
// node, sequence.launch playback:=robot), takes them from the robots' announcements; either way the team's timing
// and references are made from them here, as cosmo_generate makes them (bit for bit: the same functions).
#include <Eigen/Core>
#include <map>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::sequence {

struct TrialBasis {
  TrialSpan span;             ///< the covered scans: first and last sweep-end stamp (span.robot: the robot)
  Trajectory body_reference;  ///< the reference file as read (body poses in its frame); empty: none
};

/// The sequence's reference offset (`reference_offset`) given the anchor trial's reference as read.
Eigen::Vector3d referenceOffset(const ReferenceOffsetConfig& offset, const Trajectory& anchor_body_reference);

/// The synchronized timing of `config` (spec section 3) from its trials' spans. Throws std::runtime_error naming
/// the robot when a trial of the config has no basis.
SequenceTiming synchronizeTrials(const SequenceConfig& config, const std::map<char, TrialBasis>& trials);

/// Every trial's sensor reference in sequence time, with the sequence's reference offset (robot -> trajectory).
std::map<char, Trajectory> sensorReferences(const SequenceConfig& config, const std::map<char, TrialBasis>& trials,
                                            const SequenceTiming& timing);

}  // namespace cosmo::sequence
