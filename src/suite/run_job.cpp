#include "cosmo/suite/run_job.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/suite/child_process.hpp"
#include "cosmo/suite/config_overlay.hpp"
#include "cosmo/suite/dataset_summary.hpp"
#include "cosmo/suite/file_identity.hpp"
#include "cosmo/suite/job_record.hpp"
#include "cosmo/suite/out_dir.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

std::string flat(const std::string& id) {
  std::string s = id;
  std::replace(s.begin(), s.end(), '/', '+');
  return s;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

struct JobFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void logLine(const std::string& log, const std::string& text) { std::ofstream(log, std::ios::app) << text << "\n"; }

std::string commandText(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

/// Runs one program into the log; throws JobFailed with the reason and the log's last lines.
ChildResult runLogged(const std::vector<std::string>& argv, const std::string& log) {
  logLine(log, "$ " + commandText(argv));
  const ChildResult r = runChild(argv, log);
  if (r.exit_code != 0)
    throw JobFailed(fs::path(argv.front()).filename().string() + " failed (" + r.describe() + "); its last lines:\n" +
                    tailOfFile(log, 6));
  return r;
}

void checkDependencies(const Plan& plan, const Job& job) {
  IdentityCache cache;
  for (const auto& dep : job.depends_on) {
    const JobState s = checkJob(plan, plan.job(dep), cache);
    if (s.kind != JobState::Kind::Current) throw JobFailed("it needs " + dep + ", which is not done (" + s.reason + ")");
  }
}

/// The variants' steps on each comm model's JRL; returns the JRL that is the dataset, per comm model.
std::vector<std::string> runPostSteps(const Plan& plan, const Job& job, const std::string& tmp, const std::string& log,
                                      ChildResult& cost) {
  std::vector<std::string> jrls;
  for (const auto& comm : job.comms) {
    std::string jrl = job.jrlFile(comm);
    for (const auto& step : job.post_steps) {
      const std::string out = fs::path(jrl).stem().string() + step.suffix + ".jrl";
      std::vector<std::string> argv{(fs::path(plan.program_dir) / step.program).string(), step.verb,
                                    (fs::path(tmp) / jrl).string(), (fs::path(tmp) / out).string()};
      argv.insert(argv.end(), step.args.begin(), step.args.end());
      const ChildResult r = runLogged(argv, log);
      cost.cpu_s += r.cpu_s;
      jrl = out;
    }
    if (!job.post_steps.empty())
      runLogged({(fs::path(plan.program_dir) / "cosmo_jrl").string(), "plot", (fs::path(tmp) / jrl).string()}, log);
    jrls.push_back(jrl);
  }
  return jrls;
}

std::vector<OutputFile> hashOutputs(const std::string& dir) {
  std::vector<OutputFile> outs;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != kRecordFile)
      outs.push_back({fs::relative(e.path(), dir).string(), fs::file_size(e.path()), sha256File(e.path().string())});
  std::sort(outs.begin(), outs.end(), [](const OutputFile& a, const OutputFile& b) { return a.file < b.file; });
  return outs;
}

std::vector<std::string> generateCommand(const Plan& plan, const Job& job, const std::string& tmp,
                                         const RunJobOptions& o) {
  pipeline::GenerateRequest request = job.request;
  if (job.kind == Job::Kind::Estimate) {
    request.noise_models_out = (fs::path(tmp) / job.estimateFile()).string();
  } else {
    request.out_dir = tmp;
    request.registration_threads = o.registration_threads;
  }
  std::vector<std::string> argv{(fs::path(plan.program_dir) / "cosmo_generate").string()};
  for (auto& a : pipeline::generateArgs(request)) argv.push_back(std::move(a));
  return argv;
}

/// Everything between the lock and the move into place; returns the record.
JobRecord makeOutputs(const Plan& plan, const Job& job, const std::string& tmp, const RunJobOptions& o,
                      const std::string& log) {
  JobRecord rec;
  rec.job = job.id;
  rec.kind = job.kind == Job::Kind::Estimate ? "estimate" : "datasets";
  rec.run_id = o.run_id;
  IdentityCache cache;
  rec.inputs = inputIdentities(job, cache);
  rec.key = jobKey(job, rec.inputs);
  makeConfigOverlay(plan, job);
  rec.command = generateCommand(plan, job, tmp, o);
  ChildResult cost = runLogged(rec.command, log);
  if (job.kind == Job::Kind::Datasets) {
    const std::vector<std::string> jrls = runPostSteps(plan, job, tmp, log, cost);
    const std::vector<std::string> names = job.datasetNames();
    for (std::size_t i = 0; i < jrls.size(); ++i)
      rec.datasets.push_back(summariseDataset(tmp, jrls[i], names[i], job.comms[i]));
  }
  rec.outputs = hashOutputs(tmp);
  rec.wall_s = cost.wall_s;
  rec.cpu_s = cost.cpu_s;
  rec.peak_rss_mb = cost.peak_rss_mb;
  rec.sequence_seconds = job.seconds;
  rec.registration_threads = job.kind == Job::Kind::Datasets ? o.registration_threads : 0;
  rec.finished = utcNow();
  return rec;
}

void writeFailure(const Plan& plan, const Job& job, const RunJobOptions& o, const std::string& reason) {
  const nlohmann::json f{{"job", job.id}, {"run", o.run_id}, {"reason", reason}, {"finished", utcNow()}};
  dataset::writeFileAtomically(jobFailurePath(plan.out_dir, job.id), f.dump() + "\n");
}

}  // namespace

std::string jobLogPath(const std::string& out_dir, const std::string& job_id) {
  return suiteDir(out_dir, "logs") + "/" + flat(job_id) + ".log";
}

std::string jobFailurePath(const std::string& out_dir, const std::string& job_id) {
  return suiteDir(out_dir, "failed") + "/" + flat(job_id) + ".json";
}

std::string readFailure(const std::string& out_dir, const std::string& job_id, std::string* run_id) {
  std::ifstream in(jobFailurePath(out_dir, job_id));
  if (!in) return "";
  try {
    const nlohmann::json f = nlohmann::json::parse(in);
    if (run_id) *run_id = f.at("run").get<std::string>();
    return f.at("reason").get<std::string>();
  } catch (const std::exception&) { return "(unreadable failure record)"; }
}

JobOutcome runJob(const Plan& plan, const std::string& job_id, const RunJobOptions& o) {
  const Job* job = nullptr;
  std::string tmp;
  try {
    job = &plan.job(job_id);
    const auto lock = lockJob(plan.out_dir, job->id, true);
    IdentityCache cache;
    if (checkJob(plan, *job, cache).kind == JobState::Kind::Current) return JobOutcome::Current;
    removePartial(plan.out_dir, job->id);
    const std::string log = jobLogPath(plan.out_dir, job->id);
    std::ofstream(log, std::ios::trunc) << "cosmo_suite job " << job->id << " (run " << o.run_id << ")\n";
    checkDependencies(plan, *job);
    tmp = makeJobTmpDir(plan.out_dir, job->id);
    const JobRecord rec = makeOutputs(plan, *job, tmp, o, log);
    dataset::writeFileAtomically((fs::path(tmp) / kRecordFile).string(), rec.toJson() + "\n");
    moveIntoPlace(plan.out_dir, tmp, jobFolder(plan, *job));
    fs::remove(jobFailurePath(plan.out_dir, job->id));
    writeManifest(plan);
    return JobOutcome::Done;
  } catch (const std::exception& e) {
    std::error_code ec;
    if (!tmp.empty()) fs::remove_all(tmp, ec);
    if (job) {
      try {
        writeFailure(plan, *job, o, e.what());
      } catch (const std::exception&) {
      }
    }
    return JobOutcome::Failed;
  }
}

}  // namespace cosmo::suite
