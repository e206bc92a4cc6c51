#include "cosmo/suite/plan.hpp"

#include <algorithm>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "cosmo/common/nearest_name.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/suite/file_identity.hpp"
#include "cosmo/suite/plan_inputs.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

/// A sequence entry with its config read.
struct Resolved {
  SequenceEntry entry;
  sequence::SequenceConfig config;
  std::string data_root;  ///< what the jobs pass as --data-root ("" = none)
};

std::string layoutPart(const std::string& layout) {
  return layout == "cosmo" ? "" : layout == "mcd" ? "_mcd" : "_cumulti";
}

Resolved resolve(const SequenceEntry& e, const PlanOptions& o) {
  Resolved r;
  r.entry = e;
  if (!e.simulate.empty()) {
    r.entry.sequence = o.simulate(e);
  } else if (!e.data_root.empty() || !o.data_root.empty()) {
    r.data_root = fs::path(e.data_root).is_absolute() || o.data_root.empty()
                      ? e.data_root
                      : (fs::path(o.data_root) / e.data_root).lexically_normal().string();
    if (r.data_root.empty()) r.data_root = o.data_root;
    while (r.data_root.size() > 1 && r.data_root.back() == '/') r.data_root.pop_back();
  }
  try {
    r.config = sequence::SequenceConfig::load(r.entry.sequence, r.data_root);
  } catch (const std::exception& ex) { throw std::runtime_error(e.where + ": " + ex.what()); }
  if (r.entry.label.empty()) r.entry.label = nameSafe(r.config.name) + layoutPart(e.layout);
  return r;
}

std::vector<std::string> labels(const std::vector<Resolved>& seqs) {
  std::vector<std::string> out;
  for (const auto& s : seqs) out.push_back(s.entry.label);
  return out;
}

const Resolved& findLabel(const std::vector<Resolved>& seqs, const std::string& label, const std::string& where) {
  for (const auto& s : seqs)
    if (s.entry.label == label) return s;
  const std::string near = nearestName(label, labels(seqs));
  throw std::runtime_error(where + ": no sequence labelled '" + label + "'" +
                           (near.empty() ? "" : " (did you mean '" + near + "'?)"));
}

/// `gate_threshold` sets the gate on top of the sequence's keys: a variant that sets the gate too would be overruled.
void checkGateThresholdAlone(const SuiteFile& suite) {
  const auto has = [&](const std::string& key) {
    return std::any_of(suite.variants.begin(), suite.variants.end(), [&](const VariantAxis& a) { return a.key == key; });
  };
  if (!has("gate_threshold")) return;
  for (const char* key : {"registration", "registration.gate", "registration.min_structure_overlap"})
    if (has(key))
      throw std::runtime_error(suite.path + ": variants: give `gate_threshold` or `" + std::string(key) +
                               "`, not both (the threshold sets gate: strict and min_structure_overlap)");
}

/// Every combination of the variant axes' values (a grid, the first axis slowest); `repeats: N` is N values.
std::vector<std::vector<std::pair<std::string, VariantValue>>> variantGrid(const SuiteFile& suite) {
  std::vector<std::vector<std::pair<std::string, VariantValue>>> grid{{}};
  bool seed = false, repeats = false;
  for (const auto& axis : suite.variants) {
    seed |= axis.key == "seed";
    repeats |= axis.key == "repeats";
    std::vector<VariantValue> values = axis.values;
    if (axis.key == "repeats") {
      values.clear();
      for (unsigned long long k = 0; k < std::stoull(axis.values.front().scalar); ++k)
        values.push_back({std::to_string(k), {}, axis.values.front().where});
    }
    std::vector<std::vector<std::pair<std::string, VariantValue>>> next;
    for (const auto& combo : grid)
      for (const auto& v : values) {
        next.push_back(combo);
        next.back().emplace_back(axis.key, v);
      }
    grid = next;
  }
  if (seed && repeats) throw std::runtime_error(suite.path + ": variants: give `seed` or `repeats`, not both");
  checkGateThresholdAlone(suite);
  return grid;
}

/// The folder of the config copy that a group's registration / radio keys need (deterministic: one per set).
std::string overlayDir(const std::string& out, const Job& job) {
  std::string text;
  for (const auto& [k, v] : job.registration) text += "registration." + k + "=" + v + "\n";
  for (const auto& [k, v] : job.radio) text += "radio." + k + "=" + v + "\n";
  return (fs::path(out) / ".suite" / "config" / sha256Text(text).substr(0, 16)).string();
}

Job groupJob(const Resolved& seq, const std::vector<std::pair<std::string, VariantValue>>& combo,
             const SuiteFile& suite, const PlanOptions& o) {
  Job job;
  job.label = seq.entry.label;
  job.id = seq.entry.label;
  VariantEffect effect;
  for (const auto& [key, value] : combo) {
    std::string sub;
    const VariantKey* k = findVariantKey(key, sub);
    job.id += "_" + nameSafe(k->tag(sub, value));
    k->apply(sub, value, effect);
  }
  for (const auto& [k, v] : effect.registration)
    if (seq.config.registration.count(k))
      throw std::runtime_error(suite.path + ": variants: registration key '" + k + "' is set by the sequence " +
                               seq.config.path + " itself (its own keys go on top of a variant's)");
  job.registration = effect.registration;
  job.radio = effect.radio;
  job.post_steps = effect.post_steps;
  job.comms = suite.comms;
  pipeline::GenerateRequest& r = job.request;
  r.sequence = seq.entry.sequence;
  r.data_root = seq.data_root;
  r.comms = suite.comms;
  if (effect.seed) r.seed = *effect.seed;
  if (effect.seed_offset) r.seed = seq.config.seed + *effect.seed_offset;
  r.max_seconds = suite.max_seconds;
  for (const auto& set : effect.request) set(r);
  r.config_dir = !job.registration.empty() || !job.radio.empty() ? overlayDir(o.out_dir, job) : suite.config_dir;
  return job;
}

Job estimateJob(const EstimateEntry& e, const Resolved& seq, const SuiteFile& suite) {
  Job job;
  job.kind = Job::Kind::Estimate;
  job.id = "noise_models/" + e.name;
  job.label = seq.entry.label;
  try {
    sequence::findTrial(seq.config, e.trial);
  } catch (const std::exception& ex) { throw std::runtime_error(e.where + ".trial: " + ex.what()); }
  job.request.sequence = seq.entry.sequence;
  job.request.data_root = seq.data_root;
  job.request.config_dir = suite.config_dir;
  job.request.estimate_trial = e.trial;
  job.request.estimate_only = true;
  return job;
}

/// The estimate (job id) that each sequence label uses; checks `from` and `for`.
std::map<std::string, std::string> estimateUsers(const SuiteFile& suite, const std::vector<Resolved>& seqs) {
  std::map<std::string, std::string> users;
  for (const auto& e : suite.estimates) {
    findLabel(seqs, e.from, e.where + ".from");
    std::vector<std::string> used_by = e.used_by;
    if (used_by.empty())
      for (const auto& s : seqs)
        if (s.config.environment == e.name) used_by.push_back(s.entry.label);
    for (const auto& label : used_by) {
      findLabel(seqs, label, e.where + ".for");
      if (users.count(label))
        throw std::runtime_error(e.where + ": sequence '" + label + "' already uses the estimate " + users[label]);
      users[label] = "noise_models/" + e.name;
    }
  }
  return users;
}

void checkUniqueIds(const Plan& plan) {
  std::set<std::string> seen;
  for (const auto& j : plan.jobs)
    if (!seen.insert(j.id).second)
      throw std::runtime_error(plan.suite_path + ": two groups are named " + j.id +
                               ": give the sequences different `label:`s");
}

}  // namespace

Plan planSuite(const SuiteFile& suite, const PlanOptions& o) {
  Plan plan;
  plan.suite_path = suite.path;
  plan.suite_name = suite.name;
  plan.out_dir = o.out_dir;
  plan.config_dir = suite.config_dir.empty() ? o.default_config_dir : suite.config_dir;
  plan.program_dir = o.program_dir;
  plan.max_seconds = suite.max_seconds;
  std::vector<Resolved> seqs;
  for (const auto& e : suite.sequences) seqs.push_back(resolve(e, o));
  const std::map<std::string, std::string> users = estimateUsers(suite, seqs);
  for (const auto& e : suite.estimates) {
    const Resolved& from = findLabel(seqs, e.from, e.where + ".from");
    plan.jobs.push_back(estimateJob(e, from, suite));
    addEstimateInputs(plan, plan.jobs.back(), from.config, e.trial);
  }
  std::map<std::string, std::vector<std::string>> cold;  // group -> compressed bags not yet in the scan cache
  for (const auto& seq : seqs) {
    const std::vector<std::string> seq_cold = coldCompressedBags(seq.config);
    for (const auto& combo : variantGrid(suite)) {
      plan.jobs.push_back(groupJob(seq, combo, suite, o));
      Job& job = plan.jobs.back();
      std::string estimate_file;
      if (users.count(seq.entry.label)) {
        job.depends_on.push_back(users.at(seq.entry.label));
        estimate_file = (fs::path(jobFolder(plan, plan.job(users.at(seq.entry.label)))) /
                         plan.job(users.at(seq.entry.label)).estimateFile())
                            .string();
        job.request.noise_models = estimate_file;
      }
      addGroupInputs(plan, job, seq.config, estimate_file);
      cold[job.id] = seq_cold;
    }
  }
  orderFirstPasses(plan, cold);
  checkUniqueIds(plan);
  checkInputsExist(plan);
  return plan;
}

std::vector<std::string> Job::datasetNames() const {
  std::vector<std::string> names;
  if (kind == Kind::Datasets)
    for (const auto& c : comms) names.push_back(id + "_" + c);
  return names;
}

std::string Job::estimateFile() const { return fs::path(id).filename().string() + ".yaml"; }

const Job& Plan::job(const std::string& id) const {
  for (const auto& j : jobs)
    if (j.id == id) return j;
  throw std::runtime_error("the suite's plan has no job " + id);
}

std::string jobFolder(const Plan& plan, const Job& job) { return (fs::path(plan.out_dir) / job.id).string(); }

}  // namespace cosmo::suite
