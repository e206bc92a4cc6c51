#pragma once
// The pre-flight check's reading side (sequence/trial_check.hpp judges): what a trial's bag holds at its start,
// and the whole check of a sequence config, as cosmo_check prints it.
#include <string>

#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/trial_check.hpp"

namespace cosmo::trials {

/// Opens the trial's bag and reads its first `scans` scans on the trial's topic (never throws: problems go to
/// TrialProbe::error).
sequence::TrialProbe probeTrial(const sequence::TrialConfig& trial, std::size_t scans = 10);

/// Probes every trial, reads its reference and judges it; `text` gets the lines and the verdict. True when the
/// run can produce a labelled dataset.
bool checkSequence(const sequence::SequenceConfig& config, const std::string& noise_models, std::string& text);

/// The check of `robot`'s trial alone (robot-side playback: each robot checks its own trial), with the noise
/// models the whole sequence labels with (looked up in `config_dir`).
bool checkTrial(const sequence::SequenceConfig& config, char robot, const std::string& config_dir, std::string& text);

}  // namespace cosmo::trials
