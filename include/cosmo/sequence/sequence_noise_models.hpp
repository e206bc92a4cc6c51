#pragma once
// The noise models a run of a sequence uses (spec section 6: one model per environment, estimated from one
// trial of that environment run alone). The sequence names them, by `noise_models: FILE` or by `environment:
// NAME` (<config_dir>/noise_models/NAME.yaml); an explicit file (--noise-models, ~noise_models) overrides
// both. There is no fallback: a sequence that names neither, a file that does not exist, or one that says its
// models are unknown stops the run with a message that says how to make them. The offline driver, the player
// and the recorder node all resolve them here.
#include <stdexcept>
#include <string>

#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/sequence/sequence_config.hpp"

namespace cosmo::sequence {

/// Thrown when a sequence has no usable noise models; what() says how to make them.
struct NoiseModelsMissing : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The file a run of `sequence` reads: `override_path` when not empty, else the sequence's noise_models, else
/// <config_dir>/noise_models/<environment>.yaml. Throws NoiseModelsMissing when the sequence names neither.
std::string sequenceNoiseModelsPath(const SequenceConfig& sequence, const std::string& config_dir,
                                    const std::string& override_path = "");

/// For reports (cosmo_check): that file, or "" when the sequence names none or names it only by an environment
/// whose file does not exist. Never throws.
std::string chooseNoiseModels(const SequenceConfig& config, const std::string& config_dir,
                              const std::string& given = "");

/// Loads that file (NoiseModels::source = its path). Throws NoiseModelsMissing when it does not exist or says
/// its models are unknown, std::runtime_error naming file and key when it is malformed.
dataset::NoiseModels loadSequenceNoiseModels(const SequenceConfig& sequence, const std::string& config_dir,
                                             const std::string& override_path = "");

/// The noise models of a ROS run (player, recorder node): `explicit_path` when not empty (must exist), else
/// those of the sequence config at `sequence_path`, else those of the synthetic sequence that the generation
/// config `simulate_config` (config/sim/*.yaml, its `environment`) makes. Throws NoiseModelsMissing with the
/// how-to when none of them is given or they do not exist.
dataset::NoiseModels loadRunNoiseModels(const std::string& explicit_path, const std::string& sequence_path,
                                        const std::string& simulate_config, const std::string& config_dir);

/// Where `cosmo_generate --estimate-noise-models` writes its estimate unless told otherwise: beside the outputs,
/// <out_dir>/<environment>.noise_models.yaml (the sequence's name when it names no environment).
std::string estimatedNoiseModelsPath(const SequenceConfig& sequence, const std::string& out_dir);

/// How to make the missing models of `sequence` at `path` (the commands, one per line).
std::string howToMakeNoiseModels(const SequenceConfig& sequence, const std::string& path);

/// The trial of `sequence` that `which` names: a robot id ("c") or a trial name. Throws naming the choices.
const TrialConfig& findTrial(const SequenceConfig& sequence, const std::string& which);

}  // namespace cosmo::sequence
