#include "cosmo/trials/trial_reference.hpp"

#include "cosmo/pipeline/sequence_references.hpp"
#include "cosmo/pipeline/trial_basis.hpp"
#include "cosmo/trials/reference_file.hpp"

namespace cosmo::trials {

Trajectory readBodyReference(const pipeline::TrialConfig& trial) {
  if (trial.reference.empty()) return {};
  return readReference(trial.reference);
}

pipeline::TrialCoverage trialCoverage(const pipeline::TrialConfig& trial) {
  return pipeline::TrialCoverage(trial.name, readBodyReference(trial));
}

Eigen::Vector3d sequenceReferenceOffset(const pipeline::SequenceConfig& config) {
  const bool by_anchor = config.reference_offset.mode == pipeline::ReferenceOffsetConfig::Mode::Anchor;
  return pipeline::referenceOffset(config.reference_offset,
                                   by_anchor ? readBodyReference(config.trial(config.anchor)) : Trajectory());
}

Trajectory loadSensorReference(const pipeline::TrialConfig& trial, const pipeline::TrialTiming& timing,
                               const Eigen::Vector3d& offset) {
  if (trial.reference.empty()) return {};
  return pipeline::toSensorReference(readBodyReference(trial), trial.extrinsic, timing, offset);
}

std::map<char, Trajectory> loadSequenceReferences(const pipeline::SequenceConfig& config,
                                                  const pipeline::SequenceTiming& timing) {
  const Eigen::Vector3d offset = sequenceReferenceOffset(config);
  std::map<char, Trajectory> refs;
  for (const auto& t : config.trials) refs[t.robot] = loadSensorReference(t, timing.of(t.robot), offset);
  return refs;
}

}  // namespace cosmo::trials
