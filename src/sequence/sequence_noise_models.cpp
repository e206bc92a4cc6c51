#include "cosmo/sequence/sequence_noise_models.hpp"

#include <filesystem>
#include <sstream>

#include "cosmo/sim/simulation_params.hpp"

namespace cosmo::sequence {
namespace {

std::string sequenceLabel(const SequenceConfig& s) { return s.path.empty() ? "sequence " + s.name : s.path; }

std::string trialChoices(const SequenceConfig& s) {
  std::string out;
  for (const auto& t : s.trials) out += std::string(out.empty() ? "" : ", ") + t.robot + " (" + t.name + ")";
  return out;
}

}  // namespace

std::string sequenceNoiseModelsPath(const SequenceConfig& sequence, const std::string& config_dir,
                                    const std::string& override_path) {
  if (!override_path.empty()) return override_path;
  if (!sequence.noise_models.empty()) return sequence.noise_models;
  if (!sequence.environment.empty())
    return (std::filesystem::path(config_dir) / "noise_models" / (sequence.environment + ".yaml")).string();
  throw NoiseModelsMissing(sequenceLabel(sequence) +
                           ": names no noise models: add `environment: NAME` (config/noise_models/NAME.yaml: "
                           "ntu, kth, tuhh, synthetic, or one you make) or `noise_models: FILE` to the sequence, "
                           "or pass --noise-models FILE.\n" +
                           howToMakeNoiseModels(sequence, "config/noise_models/NAME.yaml"));
}

std::string chooseNoiseModels(const SequenceConfig& config, const std::string& config_dir, const std::string& given) {
  try {
    const std::string path = sequenceNoiseModelsPath(config, config_dir, given);
    const bool by_environment = given.empty() && config.noise_models.empty();
    return by_environment && !std::filesystem::exists(path) ? std::string() : path;
  } catch (const NoiseModelsMissing&) { return ""; }
}

dataset::NoiseModels loadSequenceNoiseModels(const SequenceConfig& sequence, const std::string& config_dir,
                                             const std::string& override_path) {
  const std::string path = sequenceNoiseModelsPath(sequence, config_dir, override_path);
  const std::string env = sequence.environment.empty() ? "" : " of environment '" + sequence.environment + "'";
  if (!std::filesystem::exists(path))
    throw NoiseModelsMissing(sequenceLabel(sequence) + ": the noise models" + env + " do not exist (" + path +
                             ": no such file).\n" + howToMakeNoiseModels(sequence, path));
  try {
    return dataset::NoiseModels::load(path);
  } catch (const dataset::NoiseModelsUnknown& e) {
    throw NoiseModelsMissing(sequenceLabel(sequence) + ": the noise models" + env + " are not known (" + path + ": " +
                             e.reason + ").\n" + howToMakeNoiseModels(sequence, path));
  }
}

dataset::NoiseModels loadRunNoiseModels(const std::string& explicit_path, const std::string& sequence_path,
                                        const std::string& simulate_config, const std::string& config_dir) {
  if (!explicit_path.empty()) {
    if (!std::filesystem::exists(explicit_path))
      throw NoiseModelsMissing("noise models " + explicit_path + ": no such file");
    try {
      return dataset::NoiseModels::load(explicit_path);
    } catch (const dataset::NoiseModelsUnknown& e) {
      throw NoiseModelsMissing(std::string(e.what()) +
                               ". Make them with cosmo_generate SEQUENCE.yaml "
                               "--estimate-noise-models TRIAL, or cosmo_noise_models RUN.jrl " +
                               explicit_path);
    }
  }
  SequenceConfig sequence;
  if (!sequence_path.empty()) {
    sequence = SequenceConfig::load(sequence_path);
  } else if (!simulate_config.empty()) {
    const sim::SimulationParams sim = sim::SimulationParams::load(simulate_config);
    sequence.path = simulate_config;
    sequence.name = sim.name;
    sequence.environment = sim.environment;
  } else {
    throw NoiseModelsMissing(
        "no noise models: give a noise-model file, or the sequence whose environment names "
        "them (environment: NAME -> config/noise_models/NAME.yaml)");
  }
  return loadSequenceNoiseModels(sequence, config_dir);
}

std::string estimatedNoiseModelsPath(const SequenceConfig& sequence, const std::string& out_dir) {
  const std::string stem = sequence.environment.empty() ? sequence.name : sequence.environment;
  return (std::filesystem::path(out_dir.empty() ? "." : out_dir) / (stem + ".noise_models.yaml")).string();
}

std::string howToMakeNoiseModels(const SequenceConfig& sequence, const std::string& path) {
  const std::string seq = sequence.path.empty() ? "SEQUENCE.yaml" : sequence.path;
  std::ostringstream out;
  out << "Make them as the paper does, from one trial of the environment run alone (spec section 6):\n"
      << "  cosmo_generate " << seq << " --estimate-noise-models TRIAL [--out DIR]\n"
      << "    (TRIAL: " << trialChoices(sequence)
      << "; runs it alone through the front-end, keeps the loop closures within 0.5 m / 0.05 rad of the reference,\n"
      << "    writes the sample covariances with the counts and thresholds to "
      << estimatedNoiseModelsPath(sequence, "DIR") << " (--noise-models-out FILE: elsewhere, e.g. " << path
      << "),\n    then generates this sequence with them)\n"
      << "  or from the JRL of a single-trial run: cosmo_noise_models RUN.jrl " << path << " --environment NAME";
  return out.str();
}

const TrialConfig& findTrial(const SequenceConfig& sequence, const std::string& which) {
  for (const auto& t : sequence.trials)
    if ((which.size() == 1 && t.robot == which[0]) || t.name == which) return t;
  throw std::runtime_error(sequenceLabel(sequence) + ": no trial '" + which +
                           "' (robot id or trial name: " + trialChoices(sequence) + ")");
}

}  // namespace cosmo::sequence
