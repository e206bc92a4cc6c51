#include "cosmo/trials/trial_probe.hpp"

#include <filesystem>
#include <set>

#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/trials/bag_format.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros2_bag.hpp"
#include "cosmo/trials/trial_reference.hpp"

namespace cosmo::trials {

namespace {

/// "name (type)" of every topic of the bag; `has` = whether `topic` is one of them (with or without its slash).
std::vector<std::string> listTopics(const sequence::TrialConfig& trial, bool& has) {
  std::set<std::string> out;
  has = false;
  auto match = [&](const std::string& name) {
    if (name == trial.topic || "/" + name == trial.topic || name == "/" + trial.topic) has = true;
  };
  if (trials::detectBagFormat(trial.bag) == trials::BagFormat::Ros1) {
    const trials::Ros1Bag bag(trial.bag);
    for (const auto& c : bag.connections()) {
      out.insert(c.topic + " (" + c.type + ")");
      match(c.topic);
    }
  } else {
    for (const auto& t : trials::listRos2Topics(trial.bag)) {
      out.insert(t.name + " (" + t.type + ")");
      match(t.name);
    }
  }
  return {out.begin(), out.end()};
}

}  // namespace

sequence::TrialProbe probeTrial(const sequence::TrialConfig& trial, std::size_t scans) {
  sequence::TrialProbe probe;
  if (!std::filesystem::exists(trial.bag)) {
    probe.error = "bag not found: " + trial.bag;
    return probe;
  }
  try {
    probe.topics = listTopics(trial, probe.topic_found);
    probe.bag_found = true;
  } catch (const std::exception& e) {
    probe.error = trial.bag + ": cannot open bag: " + e.what();
    return probe;
  }
  if (!probe.topic_found) return probe;
  try {
    auto source = openTrialScanSource(trial);
    probe.messages = source->size();
    Scan scan;
    while (probe.first_scans.size() < scans && source->next(scan)) {
      if (probe.fields.empty()) probe.fields = trials::describeFields(source->lastLayout());
      probe.points_in_messages += source->lastCounts().points;
      probe.first_scans.push_back(scan);
    }
    if (probe.first_scans.empty()) throw std::runtime_error(trial.bag + " " + trial.topic + ": no scan");
    probe.first_stamp = probe.first_scans.front().stamp;
    probe.last_stamp = readSweepEndSpan(trial).last;
  } catch (const std::exception& e) { probe.error = e.what(); }
  return probe;
}

bool checkSequence(const sequence::SequenceConfig& config, const std::string& noise_models, std::string& text) {
  std::vector<sequence::TrialCheck> checks;
  for (const auto& t : config.trials) {
    Trajectory reference;
    std::string reference_error;
    try {
      if (!t.reference.empty() && !std::filesystem::exists(t.reference))
        reference_error = t.name + ": reference not found: " + t.reference;
      else
        reference = trials::readBodyReference(t);
    } catch (const std::exception& e) { reference_error = t.name + ": " + e.what(); }
    checks.push_back(sequence::checkTrial(t, probeTrial(t), reference, reference_error, noise_models));
  }
  const bool ok = sequence::formatChecks(checks, text);
  std::string hint;
  for (const auto& c : checks)
    if (!ok && config.data_root_from == "config folder" && c.line.find("NOT FOUND") != std::string::npos)
      hint =
          "(the trials' paths are relative to the data root: give it with --data-root DIR / data_root:=DIR or "
          "COSMO_DATA_ROOT)\n";
  text = "sequence " + config.name + " (" + config.source + "), data root " + config.data_root + " (" +
         config.data_root_from + ")\n" + text + hint;
  return ok;
}

bool checkTrial(const sequence::SequenceConfig& config, char robot, const std::string& config_dir, std::string& text) {
  sequence::SequenceConfig alone = config;
  alone.trials = {config.trial(robot)};
  return checkSequence(alone, sequence::chooseNoiseModels(config, config_dir), text);
}

}  // namespace cosmo::trials
