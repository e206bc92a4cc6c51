#include "cosmo/ros/played_sequence.hpp"

#include <ros/console.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "cosmo/pipeline/built_in_sequence.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/ros/trial_probe.hpp"

namespace cosmo::ros_glue {

namespace {

std::string sequencePath(const SequenceChoice& choice) {
  if (!choice.sequence.empty()) return choice.sequence;
  const pipeline::BuiltInSequence built_in =
      pipeline::builtInSequence(choice.simulate_config, choice.simulate_out, pipeline::programDir());
  ROS_INFO("player: built-in sequence: %s (generated on the first run; several minutes)", built_in.command.c_str());
  return pipeline::writeBuiltInSequence(built_in);
}

void checkBeforePlaying(const pipeline::SequenceConfig& config) {
  std::string check;
  const bool ok = checkSequence(config, pipeline::chooseNoiseModels(config, pipeline::defaultConfigDir()), check);
  ROS_INFO("player: pre-flight check:\n%s", check.c_str());
  if (!ok) throw std::runtime_error("the pre-flight check failed (above)");
}

}  // namespace

std::vector<char> PlayedSequence::robots() const {
  std::vector<char> r;
  for (const auto& t : config.trials) r.push_back(t.robot);
  return r;
}

pipeline::SequenceConfig loadSequenceChoice(const SequenceChoice& choice) {
  pipeline::SequenceConfig config = pipeline::SequenceConfig::load(sequencePath(choice), choice.data_root);
  if (choice.seed >= 0) config.seed = static_cast<unsigned long long>(choice.seed);
  return config;
}

std::map<char, pipeline::TrialBasis> readTrialBases(const pipeline::SequenceConfig& config) {
  checkBeforePlaying(config);
  std::map<char, pipeline::TrialBasis> basis;
  for (const auto& t : config.trials) basis[t.robot] = readTrialBasis(t);
  return basis;
}

PlayedSequence resolvePlayedSequence(const SequenceChoice& choice, const TrialBases& trial_bases) {
  PlayedSequence s;
  s.config = loadSequenceChoice(choice);
  publishTeamRobots(s.robots());
  ROS_INFO("player: noise models %s",
           pipeline::loadSequenceNoiseModels(s.config, choice.config_dir, choice.noise_models).describe().c_str());
  const std::map<char, pipeline::TrialBasis> basis = trial_bases(s.config);
  s.timing = pipeline::synchronizeTrials(s.config, basis);
  s.references = pipeline::sensorReferences(s.config, basis, s.timing);
  if (!s.config.registration.empty())
    ROS_INFO("player: the sequence's own registration keys apply (%s)", s.config.path.c_str());
  publishResolvedSequence(std::filesystem::absolute(s.config.path).string(), s.config.seed,
                          std::filesystem::absolute(s.config.data_root).string(), s.config.registration);
  s.end = choice.max_seconds > 0 ? std::min(s.timing.end(), s.timing.start() + toStampNs(choice.max_seconds))
                                 : s.timing.end();
  return s;
}

}  // namespace cosmo::ros_glue
