#include "cosmo/trials/trial_reference.hpp"

#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/sequence/trial_basis.hpp"
#include "cosmo/trials/reference_file.hpp"

namespace cosmo::trials {

Trajectory readBodyReference(const sequence::TrialConfig& trial) {
  if (trial.reference.empty()) return {};
  return readReference(trial.reference);
}

sequence::TrialCoverage trialCoverage(const sequence::TrialConfig& trial) {
  return sequence::TrialCoverage(trial.name, readBodyReference(trial));
}

Eigen::Vector3d sequenceReferenceOffset(const sequence::SequenceConfig& config) {
  const bool by_anchor = config.reference_offset.mode == sequence::ReferenceOffsetConfig::Mode::Anchor;
  return sequence::referenceOffset(config.reference_offset,
                                   by_anchor ? readBodyReference(config.trial(config.anchor)) : Trajectory());
}

Trajectory loadSensorReference(const sequence::TrialConfig& trial, const sequence::TrialTiming& timing,
                               const Eigen::Vector3d& offset) {
  if (trial.reference.empty()) return {};
  return sequence::toSensorReference(readBodyReference(trial), trial.extrinsic, timing, offset);
}

std::map<char, Trajectory> loadSequenceReferences(const sequence::SequenceConfig& config,
                                                  const sequence::SequenceTiming& timing) {
  const Eigen::Vector3d offset = sequenceReferenceOffset(config);
  std::map<char, Trajectory> refs;
  for (const auto& t : config.trials) refs[t.robot] = loadSensorReference(t, timing.of(t.robot), offset);
  return refs;
}

}  // namespace cosmo::trials
