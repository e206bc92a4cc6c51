#include "cosmo/suite/status.hpp"

#include <algorithm>

#include "cosmo/suite/job_record.hpp"
#include "cosmo/suite/out_dir.hpp"
#include "cosmo/suite/run_job.hpp"
#include "cosmo/suite/slurm.hpp"

namespace cosmo::suite {
namespace {

/// "queued in Slurm (PENDING)" when the latest submission has a task of `job_id` in the queue.
std::string queued(const SlurmSubmission& sub, const std::map<std::string, std::string>& queue,
                   const std::string& job_id) {
  for (const auto& a : sub.arrays)
    for (std::size_t i = 0; i < a.jobs.size(); ++i)
      if (a.jobs[i] == job_id) {
        const auto it = queue.find(a.slurm_id + "_" + std::to_string(i));
        if (it != queue.end()) return "queued in Slurm (" + it->second + ", task " + it->first + ")";
      }
  return "";
}

}  // namespace

JobStatuses folderStatuses(const Plan& plan, const std::string& run_id) {
  JobStatuses statuses;
  IdentityCache cache;
  SlurmSubmission sub;
  const bool submitted = readLastSubmission(plan.out_dir, sub);
  const auto queue = submitted ? slurmQueue(sub) : std::map<std::string, std::string>{};
  for (const auto& job : plan.jobs) {
    std::string failed_run;
    const std::string failure = readFailure(plan.out_dir, job.id, &failed_run);
    const JobState s = checkJob(plan, job, cache);
    JobRecord rec;
    std::string status;
    if (s.kind == JobState::Kind::Current && readRecord(jobFolder(plan, job), rec))
      status = run_id.empty() || rec.run_id == run_id ? "done" : "skipped as current";
    else if (!lockJob(plan.out_dir, job.id, false))
      status = "running";
    else if (submitted && !(status = queued(sub, queue, job.id)).empty())
      ;
    else if (!failure.empty() && (run_id.empty() || failed_run == run_id))
      status = "failed: " + failure;
    else
      status = s.kind == JobState::Kind::Stale ? "stale: " + s.reason : "missing";
    statuses[job.id] = status;
  }
  return statuses;
}

ReportInput reportInput(const Plan& plan, const JobStatuses& statuses, const PaperTable* paper,
                        const std::string& note) {
  ReportInput in;
  in.suite_name = plan.suite_name;
  in.suite_path = plan.suite_path;
  in.out_dir = plan.out_dir;
  in.note = note;
  in.paper = paper;
  for (const auto& job : plan.jobs) {
    ReportJob rj;
    rj.job = &job;
    rj.status = statuses.count(job.id) ? statuses.at(job.id) : "missing";
    JobRecord rec;
    if ((rj.status == "done" || rj.status.rfind("skipped", 0) == 0) && readRecord(jobFolder(plan, job), rec))
      rj.record = rec;
    in.jobs.push_back(rj);
  }
  return in;
}

std::string statusCounts(const Plan& plan, const JobStatuses& statuses) {
  std::size_t total = 0, done = 0, skipped = 0, failed = 0, other = 0;
  for (const auto& job : plan.jobs) {
    if (job.kind == Job::Kind::Estimate) continue;
    const std::size_t n = job.comms.size();
    const std::string& s = statuses.count(job.id) ? statuses.at(job.id) : "missing";
    total += n;
    if (s == "done")
      done += n;
    else if (s.rfind("skipped", 0) == 0)
      skipped += n;
    else if (s.rfind("failed", 0) == 0 || s.rfind("not run", 0) == 0)
      failed += n;
    else
      other += n;
  }
  std::string out = std::to_string(total) + " datasets: " + std::to_string(done) + " done, " + std::to_string(skipped) +
                    " skipped as current, " + std::to_string(failed) + " failed";
  if (other) out += ", " + std::to_string(other) + " not made (missing, stale, queued or running)";
  return out;
}

}  // namespace cosmo::suite
