#pragma once
// The pre-flight check's reading side (pipeline/trial_check.hpp judges): what a trial's bag holds at its start,
// and the whole check of a sequence config, as cosmo_check prints it.
#include <string>

#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/trial_check.hpp"

namespace cosmo::ros_glue {

/// Opens the trial's bag and reads its first `scans` scans on the trial's topic (never throws: problems go to
/// TrialProbe::error).
pipeline::TrialProbe probeTrial(const pipeline::TrialConfig& trial, std::size_t scans = 10);

/// Probes every trial, reads its reference and judges it; `text` gets the lines and the verdict. True when the
/// run can produce a labelled dataset.
bool checkSequence(const pipeline::SequenceConfig& config, const std::string& noise_models, std::string& text);

}  // namespace cosmo::ros_glue
