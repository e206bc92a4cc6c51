#pragma once
// A suite run on this machine: which jobs are current (skipped), stale or partial (redone, and why), then the
// others side by side as the scheduler allows, each as its own process (`cosmo_suite job`, the command a Slurm task
// runs), with a progress line and an ETA.
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "cosmo/suite/plan.hpp"
#include "cosmo/suite/scheduler.hpp"

namespace cosmo::suite {

struct LocalRunOptions {
  SlotPolicy policy;
  std::string run_id;
  std::string self_exe;   ///< cosmo_suite's path
  std::string plan_path;  ///< the plan as the job processes read it
  double progress_every_s = 30.0;
};

/// Each job's status at the end of a run, as the report shows it ("done", "skipped as current", "failed: ...",
/// "not run: ...").
using JobStatuses = std::map<std::string, std::string>;

/// What a job's folder holds now, before anything runs: "current", "stale: <why>", "partial: <job> was killed
/// while it was written", "missing". Removes partial folders (with the job's lock held).
std::map<std::string, std::string> surveyJobs(const Plan& plan);

/// The jobs a run starts: those not current, and those waiting for one that runs (its output may change).
std::vector<std::string> jobsToRun(const Plan& plan, const std::map<std::string, std::string>& survey);

/// Runs the plan's jobs that are not current; prints what it does to `out`. Returns every job's status.
JobStatuses runLocal(const Plan& plan, const LocalRunOptions& options, std::ostream& out);

}  // namespace cosmo::suite
