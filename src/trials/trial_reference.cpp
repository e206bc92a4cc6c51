#include "cosmo/trials/trial_reference.hpp"

#include "cosmo/pipeline/sequence_references.hpp"
#include "cosmo/trials/reference_file.hpp"

namespace cosmo::trials {

Trajectory loadSensorReference(const pipeline::TrialConfig& trial, const pipeline::TrialTiming& timing) {
  if (trial.reference.empty()) return {};
  return pipeline::toSensorReference(readReference(trial.reference), trial.extrinsic, timing);
}

}  // namespace cosmo::trials
