// The plan as JSON: written by the suite before it runs or submits anything, read by each job process (local or a
// Slurm task), so that every job runs exactly what was planned.
#include <nlohmann/json.hpp>

#include <stdexcept>

#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {
namespace {

using nlohmann::json;

json toJson(const Job& j) {
  json steps = json::array();
  for (const auto& s : j.post_steps) steps.push_back({{"program", s.program}, {"verb", s.verb}, {"args", s.args}, {"suffix", s.suffix}});
  json inputs = json::array();
  for (const auto& in : j.inputs) inputs.push_back({{"what", in.what}, {"path", in.path}, {"always_hash", in.always_hash}});
  return {{"kind", j.kind == Job::Kind::Estimate ? "estimate" : "datasets"},
          {"id", j.id},
          {"label", j.label},
          {"sequence", j.sequence},
          {"sequence_name", j.sequence_name},
          {"comms", j.comms},
          {"args", pipeline::generateArgs(j.request)},
          {"registration", j.registration},
          {"radio", j.radio},
          {"post_steps", steps},
          {"depends_on", j.depends_on},
          {"after", j.after},
          {"inputs", inputs},
          {"robots", j.robots},
          {"seconds", j.seconds}};
}

Job jobFromJson(const json& o) {
  Job j;
  j.kind = o.at("kind").get<std::string>() == "estimate" ? Job::Kind::Estimate : Job::Kind::Datasets;
  j.id = o.at("id").get<std::string>();
  j.label = o.at("label").get<std::string>();
  j.sequence = o.at("sequence").get<std::string>();
  j.sequence_name = o.at("sequence_name").get<std::string>();
  j.comms = o.at("comms").get<std::vector<std::string>>();
  j.request = pipeline::generateRequestFromArgs(o.at("args").get<std::vector<std::string>>());
  j.registration = o.at("registration").get<std::map<std::string, std::string>>();
  j.radio = o.at("radio").get<std::map<std::string, std::string>>();
  for (const auto& s : o.at("post_steps"))
    j.post_steps.push_back({s.at("program").get<std::string>(), s.at("verb").get<std::string>(),
                            s.at("args").get<std::vector<std::string>>(), s.at("suffix").get<std::string>()});
  j.depends_on = o.at("depends_on").get<std::vector<std::string>>();
  j.after = o.at("after").get<std::vector<std::string>>();
  for (const auto& in : o.at("inputs"))
    j.inputs.push_back({in.at("what").get<std::string>(), in.at("path").get<std::string>(), in.at("always_hash").get<bool>()});
  j.robots = o.at("robots").get<int>();
  j.seconds = o.at("seconds").get<double>();
  return j;
}

}  // namespace

std::string Plan::toJson() const {
  json jobs_json = json::array();
  for (const auto& j : jobs) jobs_json.push_back(suite::toJson(j));
  const json o{{"suite_path", suite_path}, {"suite_name", suite_name}, {"out_dir", out_dir},
               {"config_dir", config_dir}, {"program_dir", program_dir}, {"max_seconds", max_seconds},
               {"jobs", jobs_json}};
  return o.dump(1) + "\n";
}

Plan Plan::fromJson(const std::string& text, const std::string& where) {
  try {
    const json o = json::parse(text);
    Plan p;
    p.suite_path = o.at("suite_path").get<std::string>();
    p.suite_name = o.at("suite_name").get<std::string>();
    p.out_dir = o.at("out_dir").get<std::string>();
    p.config_dir = o.at("config_dir").get<std::string>();
    p.program_dir = o.at("program_dir").get<std::string>();
    p.max_seconds = o.at("max_seconds").get<double>();
    for (const auto& j : o.at("jobs")) p.jobs.push_back(jobFromJson(j));
    return p;
  } catch (const json::exception& e) { throw std::runtime_error(where + ": not a suite plan: " + e.what()); }
}

}  // namespace cosmo::suite
