#include "cosmo/suite/plan_inputs.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "cosmo/comm/comm_model.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/trials/bag_format.hpp"
#include "cosmo/trials/reference_file.hpp"
#include "cosmo/trials/scan_cache.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

/// The program and the project's shared libraries beside it (<lib>/cosmo/<program>, <lib>/libcosmo_*.so): the
/// algorithms live in the libraries, so a rebuilt library changes what the program writes.
void addProgram(const Plan& plan, Job& job, const std::string& name) {
  job.inputs.push_back({"program " + name, (fs::path(plan.program_dir) / name).string(), true});
  const fs::path lib_dir = fs::path(plan.program_dir).parent_path();
  std::vector<std::string> libs;
  if (fs::is_directory(lib_dir))
    for (const auto& e : fs::directory_iterator(lib_dir)) {
      const std::string f = e.path().filename().string();
      if (f.rfind("libcosmo_", 0) == 0 && e.path().extension() == ".so") libs.push_back(e.path().string());
    }
  std::sort(libs.begin(), libs.end());
  for (const auto& l : libs)
    if (std::none_of(job.inputs.begin(), job.inputs.end(), [&](const InputFile& f) { return f.path == l; }))
      job.inputs.push_back({"library " + fs::path(l).filename().string(), l, true});
}

void addTrial(Job& job, const sequence::TrialConfig& t) {
  job.inputs.push_back({std::string("bag ") + t.robot, t.bag});
  if (!t.reference.empty()) job.inputs.push_back({std::string("reference ") + t.robot, t.reference});
}

void addFrontendConfig(const Plan& plan, Job& job) {
  for (const char* f : {"frontend.yaml", "odometry.yaml", "place_recognition.yaml", "registration.yaml"})
    if (fs::exists(fs::path(plan.config_dir) / f))
      job.inputs.push_back({std::string("config ") + f, (fs::path(plan.config_dir) / f).string()});
}

/// The noise-model file of a group that uses no estimate; stops when the sequence has no usable models.
std::string sequenceNoiseModels(const Plan& plan, const sequence::SequenceConfig& config) {
  try {
    sequence::loadSequenceNoiseModels(config, plan.config_dir);
    return sequence::sequenceNoiseModelsPath(config, plan.config_dir);
  } catch (const sequence::NoiseModelsMissing& e) {
    throw std::runtime_error(plan.suite_path + ": " + e.what() +
                             "\nOr let the suite estimate them first: a `noise_models:` entry (config/suites/"
                             "cosmo_bench.yaml has one for cu_boulder).");
  }
}

}  // namespace

void addGroupInputs(const Plan& plan, Job& job, const sequence::SequenceConfig& config,
                    const std::string& estimate_file) {
  job.sequence = config.path;
  job.sequence_name = config.name;
  addProgram(plan, job, "cosmo_generate");
  for (const auto& step : job.post_steps)
    if (std::none_of(job.inputs.begin(), job.inputs.end(), [&](const InputFile& f) { return f.what == "program " + step.program; }))
      addProgram(plan, job, step.program);
  job.inputs.push_back({"sequence", config.path});
  for (const auto& t : config.trials) addTrial(job, t);
  addFrontendConfig(plan, job);
  for (const auto& c : job.comms) {
    const comm::CommModel model = comm::resolveCommModel(c, plan.config_dir);
    if (!model.file.empty()) job.inputs.push_back({"config comm/" + c + ".yaml", model.file});
  }
  job.inputs.push_back(
      {"noise models", estimate_file.empty() ? sequenceNoiseModels(plan, config) : estimate_file});
  job.robots = static_cast<int>(config.trials.size());
  job.seconds = estimatedSequenceSeconds(config);
  if (plan.max_seconds > 0) job.seconds = std::min(job.seconds, plan.max_seconds);
}

void addEstimateInputs(const Plan& plan, Job& job, const sequence::SequenceConfig& config, const std::string& trial) {
  job.sequence = config.path;
  job.sequence_name = config.name;
  addProgram(plan, job, "cosmo_generate");
  job.inputs.push_back({"sequence", config.path});
  const sequence::TrialConfig& t = sequence::findTrial(config, trial);
  addTrial(job, t);
  addFrontendConfig(plan, job);
  job.robots = 1;
  sequence::SequenceConfig alone = config;
  alone.trials = {t};
  job.seconds = estimatedSequenceSeconds(alone);
}

std::vector<std::string> coldCompressedBags(const sequence::SequenceConfig& config) {
  std::vector<std::string> cold;
  const std::string dir = trials::scanCacheDir();
  if (dir.empty()) return cold;  // no cache: every run decompresses
  for (const auto& t : config.trials) {
    try {
      if (!fs::is_regular_file(t.bag) || trials::detectBagFormat(t.bag) != trials::BagFormat::Ros1 ||
          !trials::ros1ChunksCompressed(t.bag))
        continue;
    } catch (const std::exception&) {
      continue;  // the run reports a bag it cannot read
    }
    if (!fs::exists(trials::scanCachePath(dir, t.bag, t.topic, t.stamp_at_end))) cold.push_back(t.bag);
  }
  return cold;
}

void orderFirstPasses(Plan& plan, const std::map<std::string, std::vector<std::string>>& cold) {
  std::map<std::string, std::string> first;  // bag -> the group that decompresses it
  for (auto& job : plan.jobs) {
    const auto it = cold.find(job.id);
    if (job.kind != Job::Kind::Datasets || it == cold.end()) continue;
    for (const auto& bag : it->second) {
      const auto owner = first.find(bag);
      if (owner == first.end())
        first[bag] = job.id;
      else if (std::find(job.after.begin(), job.after.end(), owner->second) == job.after.end())
        job.after.push_back(owner->second);
    }
  }
}

void checkInputsExist(const Plan& plan) {
  std::string missing;
  std::size_t count = 0;
  for (const auto& job : plan.jobs)
    for (const auto& in : job.inputs) {
      const bool estimate = std::any_of(job.depends_on.begin(), job.depends_on.end(), [&](const std::string& d) {
        return in.path.rfind(jobFolder(plan, plan.job(d)), 0) == 0;
      });
      if (estimate || fs::exists(in.path) || missing.find(in.path + "\n") != std::string::npos) continue;
      if (++count <= 20) missing += "  " + job.label + ": " + in.what + " " + in.path + "\n";
    }
  if (count == 0) return;
  throw std::runtime_error(plan.suite_path + ": " + std::to_string(count) + " input file(s) do not exist" +
                           (count > 20 ? " (the first 20)" : "") + ":\n" + missing +
                           "Give the folder of the downloads with --data-root (docs/suite.md).");
}

double estimatedSequenceSeconds(const sequence::SequenceConfig& config) {
  double longest = 0.0;
  for (const auto& t : config.trials) {
    if (t.reference.empty() || !fs::exists(t.reference)) continue;
    try {
      const Trajectory ref = trials::readReference(t.reference);
      if (!ref.empty()) longest = std::max(longest, toSeconds(ref.endStamp() - ref.startStamp()));
    } catch (const std::exception&) {  // the run itself reports a bad reference
    }
  }
  return longest;
}

}  // namespace cosmo::suite
