#include "cosmo/trials/trial_probe.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/trials/bag_format.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros2_bag.hpp"
#include "cosmo/trials/trial_reference.hpp"

namespace cosmo::trials {

namespace {

/// "name (type)" of every topic of the bag (of `format`); `has` = whether `topic` is one of them (with or without
/// its slash).
std::vector<std::string> listTopics(const sequence::TrialConfig& trial, trials::BagFormat format, bool& has) {
  std::set<std::string> out;
  has = false;
  auto match = [&](const std::string& name) {
    if (name == trial.topic || "/" + name == trial.topic || name == "/" + trial.topic) has = true;
  };
  if (format == trials::BagFormat::Ros1) {
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
  using sequence::BagState;
  sequence::TrialProbe probe;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(trial.bag, ec)) {
    probe.error = "bag not found: " + trial.bag;
    return probe;
  }
  if (!fs::is_directory(trial.bag, ec)) {
    if (!fs::is_regular_file(trial.bag, ec)) {
      probe.bag = BagState::Unreadable;
      probe.error = trial.bag + ": not a regular file (a bag is a file, or a ROS 2 bag's folder)";
      return probe;
    }
    if (!std::ifstream(trial.bag, std::ios::binary)) {
      probe.bag = BagState::Unreadable;
      probe.error = trial.bag + ": cannot be read (" + std::strerror(errno) + "): check its permissions";
      return probe;
    }
    if (fs::file_size(trial.bag, ec) == 0) {
      probe.bag = BagState::NotABag;
      probe.error = trial.bag + ": an empty file (0 bytes), not a bag: its recording never started or was not copied";
      return probe;
    }
  }
  trials::BagFormat format{};
  try {
    format = trials::detectBagFormat(trial.bag);
  } catch (const std::exception& e) {
    probe.bag = BagState::NotABag;
    probe.error = e.what();
    return probe;
  }
  try {
    probe.topics = listTopics(trial, format, probe.topic_found);
  } catch (const std::exception& e) {
    probe.bag = BagState::Damaged;
    probe.error = trial.bag + ": cannot open bag: " + e.what();
    return probe;
  }
  if (probe.topics.empty()) {
    probe.bag = BagState::Empty;
    probe.error = trial.bag +
                  ": a valid bag that records nothing (no connections, no messages): record the trial "
                  "again or name the bag that holds it";
    return probe;
  }
  probe.bag = BagState::Ok;
  if (!probe.topic_found) return probe;
  try {
    auto source = openTrialScanSource(trial);
    probe.messages = source->size();
    if (probe.messages == 0) return probe;  // an empty topic: the check says so
    Scan scan;
    while (probe.first_scans.size() < scans && source->next(scan)) {
      if (probe.fields.empty())
        probe.fields = trials::describeFields(source->lastLayout()) + " (" +
                       trials::pointConventions(source->lastLayout()).describe() + ")";
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
