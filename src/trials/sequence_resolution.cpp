#include "cosmo/trials/sequence_resolution.hpp"

#include <algorithm>
#include <stdexcept>

#include "cosmo/sequence/built_in_sequence.hpp"
#include "cosmo/common/config_dir.hpp"
#include "cosmo/sequence/gate_threshold.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/trials/trial_probe.hpp"

namespace cosmo::trials {

namespace {

std::string configDir(const SequenceChoice& choice) {
  return choice.config_dir.empty() ? cosmo::defaultConfigDir() : choice.config_dir;
}

}  // namespace

sequence::SequenceConfig loadSequence(const SequenceChoice& choice, const Say& say) {
  std::string path = choice.sequence;
  if (path.empty()) {
    const sequence::BuiltInSequence built_in =
        sequence::builtInSequence(choice.simulate_config, choice.simulate_out, sequence::programDir());
    if (say) say("built-in sequence: " + built_in.command + " (generated on the first run; several minutes)");
    path = sequence::writeBuiltInSequence(built_in);
  }
  sequence::SequenceConfig config = sequence::SequenceConfig::load(path, choice.data_root);
  if (choice.seed) config.seed = *choice.seed;
  if (choice.gate_threshold) sequence::applyGateThreshold(config, *choice.gate_threshold);
  return config;
}

std::string noiseModelsSource(const SequenceChoice& choice, const sequence::SequenceConfig& config) {
  if (!choice.estimate_trial.empty()) return "estimated first from trial " + choice.estimate_trial;
  return sequence::chooseNoiseModels(config, configDir(choice), choice.noise_models);
}

std::map<char, sequence::TrialBasis> readTrialBases(const sequence::SequenceConfig& config) {
  std::map<char, sequence::TrialBasis> basis;
  for (const auto& t : config.trials) basis[t.robot] = readTrialBasis(t);
  return basis;
}

std::vector<char> ResolvedSequence::robots() const {
  std::vector<char> r;
  for (const auto& t : config.trials) r.push_back(t.robot);
  return r;
}

ResolvedSequence resolveSequence(const SequenceChoice& choice, const TrialBases& bases, const Say& say) {
  ResolvedSequence s;
  s.config = loadSequence(choice, say);
  s.noise_source = noiseModelsSource(choice, s.config);
  if (choice.estimate_trial.empty())
    s.noise = sequence::loadSequenceNoiseModels(s.config, configDir(choice), choice.noise_models);
  if (choice.check) {
    const bool ok = checkSequence(s.config, s.noise_source, s.check_report);
    if (!ok) throw PreflightFailed(s.check_report);
  }
  const std::map<char, sequence::TrialBasis> basis = bases(s.config);
  s.timing = sequence::synchronizeTrials(s.config, basis);
  s.references = sequence::sensorReferences(s.config, basis, s.timing);
  if (say)
    for (const auto& t : s.config.trials) {
      std::string off;
      try {
        off = trialDewarpOff(t);
      } catch (const std::exception&) {}  // its bag is not here (robot-side playback): the robot's side reads it
      if (!off.empty()) say(std::string("robot ") + t.robot + " (trial " + t.name + "): " + off);
    }
  s.end = choice.max_seconds > 0 ? std::min(s.timing.end(), s.timing.start() + toStampNs(choice.max_seconds))
                                 : s.timing.end();
  return s;
}

}  // namespace cosmo::trials
