#include "cosmo/suite/job_record.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosmo/suite/file_identity.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

using nlohmann::json;

json summaryJson(const DatasetSummary& d) {
  return {{"name", d.name},
          {"comm", d.comm},
          {"jrl", d.jrl},
          {"figure", d.figure},
          {"duration_s", d.duration_s},
          {"length_m", d.length_m},
          {"lc", d.lc},
          {"lc_outliers", d.lc_outliers},
          {"irlc", d.irlc},
          {"irlc_outliers", d.irlc_outliers},
          {"labelled", d.labelled},
          {"violations", d.violations},
          {"inliers_ate_m", d.inliers_ate_m},
          {"init_ate_m", d.init_ate_m},
          {"solve_note", d.solve_note}};
}

DatasetSummary summaryFromJson(const json& o) {
  DatasetSummary d;
  d.name = o.at("name").get<std::string>();
  d.comm = o.at("comm").get<std::string>();
  d.jrl = o.at("jrl").get<std::string>();
  d.figure = o.at("figure").get<std::string>();
  d.duration_s = o.at("duration_s").get<double>();
  d.length_m = o.at("length_m").get<double>();
  d.lc = o.at("lc").get<std::size_t>();
  d.lc_outliers = o.at("lc_outliers").get<std::size_t>();
  d.irlc = o.at("irlc").get<std::size_t>();
  d.irlc_outliers = o.at("irlc_outliers").get<std::size_t>();
  d.labelled = o.at("labelled").get<bool>();
  d.violations = o.at("violations").get<std::size_t>();
  d.inliers_ate_m = o.at("inliers_ate_m").get<double>();
  d.init_ate_m = o.at("init_ate_m").get<double>();
  d.solve_note = o.at("solve_note").get<std::string>();
  return d;
}

/// Why the recorded inputs differ from the current ones ("" when they do not).
std::string inputChange(const std::map<std::string, std::string>& recorded,
                        const std::map<std::string, std::string>& now) {
  for (const auto& [what, id] : now) {
    const auto it = recorded.find(what);
    if (it == recorded.end()) return "new input: " + what;
    if (it->second != id) return (id == "missing" ? "input missing: " : "input changed: ") + what;
  }
  for (const auto& [what, id] : recorded)
    if (!now.count(what)) return "input no longer read: " + what;
  return "";
}

}  // namespace

std::string JobRecord::toJson() const {
  json outs = json::array();
  for (const auto& o : outputs) outs.push_back({{"file", o.file}, {"size", o.size}, {"sha256", o.sha256}});
  json sums = json::array();
  for (const auto& d : datasets) sums.push_back(summaryJson(d));
  const json o{{"job", job},         {"kind", kind},         {"key", key},
               {"run", run_id},      {"finished", finished}, {"command", command},
               {"inputs", inputs},   {"outputs", outs},      {"datasets", sums},
               {"wall_s", wall_s},   {"cpu_s", cpu_s},       {"peak_rss_mb", peak_rss_mb},
               {"sequence_s", sequence_seconds}, {"registration_threads", registration_threads}};
  return o.dump();
}

JobRecord JobRecord::fromJson(const std::string& text, const std::string& where) {
  try {
    const json o = json::parse(text);
    JobRecord r;
    r.job = o.at("job").get<std::string>();
    r.kind = o.at("kind").get<std::string>();
    r.key = o.at("key").get<std::string>();
    r.run_id = o.at("run").get<std::string>();
    r.finished = o.at("finished").get<std::string>();
    r.command = o.at("command").get<std::vector<std::string>>();
    r.inputs = o.at("inputs").get<std::map<std::string, std::string>>();
    for (const auto& f : o.at("outputs"))
      r.outputs.push_back({f.at("file").get<std::string>(), f.at("size").get<std::uintmax_t>(),
                           f.at("sha256").get<std::string>()});
    for (const auto& d : o.at("datasets")) r.datasets.push_back(summaryFromJson(d));
    r.wall_s = o.at("wall_s").get<double>();
    r.cpu_s = o.at("cpu_s").get<double>();
    r.peak_rss_mb = o.at("peak_rss_mb").get<double>();
    r.sequence_seconds = o.at("sequence_s").get<double>();
    r.registration_threads = o.at("registration_threads").get<unsigned>();
    return r;
  } catch (const json::exception& e) { throw std::runtime_error(where + ": not a suite record: " + e.what()); }
}

std::string IdentityCache::get(const InputFile& in) {
  const auto it = known_.find(in.path);
  if (it != known_.end()) return it->second;
  std::string id;
  if (in.always_hash && fs::is_regular_file(in.path))
    id = "sha256:" + sha256File(in.path);
  else
    id = fileIdentity(in.path);
  return known_[in.path] = id;
}

std::map<std::string, std::string> inputIdentities(const Job& job, IdentityCache& cache) {
  std::map<std::string, std::string> ids;
  for (const auto& in : job.inputs) ids[in.what + " " + in.path] = cache.get(in);
  return ids;
}

std::string jobKey(const Job& job, const std::map<std::string, std::string>& identities) {
  std::string text = std::string(job.kind == Job::Kind::Estimate ? "estimate" : "datasets") + "\n";
  for (const auto& a : pipeline::generateArgs(job.request)) text += "arg " + a + "\n";
  for (const auto& [k, v] : job.registration) text += "registration " + k + "=" + v + "\n";
  for (const auto& [k, v] : job.radio) text += "radio " + k + "=" + v + "\n";
  for (const auto& s : job.post_steps) {
    text += "step " + s.program + " " + s.verb;
    for (const auto& a : s.args) text += " " + a;
    text += " > " + s.suffix + "\n";
  }
  for (const auto& [what, id] : identities) text += "input " + what + " " + id + "\n";
  return sha256Text(text);
}

bool readRecord(const std::string& folder, JobRecord& record) {
  const fs::path path = fs::path(folder) / kRecordFile;
  if (!fs::exists(path)) return false;
  try {
    record = JobRecord::fromJson(readWholeFileOrEmpty(path.string()), path.string());
    return true;
  } catch (const std::exception&) { return false; }
}

JobState checkJob(const Plan& plan, const Job& job, IdentityCache& cache) {
  const std::string folder = jobFolder(plan, job);
  if (!fs::exists(folder)) return {JobState::Kind::Missing, "not made yet"};
  JobRecord record;
  if (!readRecord(folder, record)) return {JobState::Kind::Stale, "its folder has no readable " + std::string(kRecordFile)};
  const auto ids = inputIdentities(job, cache);
  if (record.key != jobKey(job, ids)) {
    const std::string change = inputChange(record.inputs, ids);
    return {JobState::Kind::Stale, change.empty() ? "parameters changed" : change};
  }
  for (const auto& out : record.outputs) {
    const fs::path p = fs::path(folder) / out.file;
    if (!fs::exists(p)) return {JobState::Kind::Stale, "output missing: " + out.file};
    if (fs::file_size(p) != out.size || sha256File(p.string()) != out.sha256)
      return {JobState::Kind::Stale, "output changed: " + out.file};
  }
  return {JobState::Kind::Current, ""};
}

}  // namespace cosmo::suite
