#pragma once
// A suite on a Slurm cluster: one array task per job that is not current (a dataset group: its comm models share
// one odometry pass, as on one machine; a noise-model estimate), each running `cosmo_suite job` exactly as a local
// run does, so the resume rules and the outputs are the same. The jobs go in waves, one array each: wave 0 holds
// the jobs that wait for nothing (the estimates among them), wave k those that wait for a job of wave k - 1 (the
// groups that use an estimate, a group that starts after the first pass over a bag it shares), with
// --dependency=afterany on the arrays of the jobs they wait for (afterany: a task whose estimate failed stops with
// that reason rather than waiting in the queue for ever). A last job writes the manifest and the report once every
// array has ended. The submission is kept in .suite/slurm/<run>/submitted.json for `cosmo_suite
// status`. The output folder and the programs must be at the same paths on every node (a shared file system).
#include <map>
#include <string>
#include <vector>

#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

struct SlurmOptions {
  std::vector<std::string> sbatch_options;  ///< the user's, given to every sbatch (they win over ours)
  std::string self_exe, plan_path, run_id;
  unsigned cpus_per_task = 0;  ///< 0: a job's width (robots + 1), at most the largest node's CPUs
};

/// One sbatch submission: its Slurm job id and the suite jobs of its array tasks (in task order).
struct SlurmArray {
  std::string name, slurm_id;
  std::vector<std::string> jobs;
};

struct SlurmSubmission {
  std::string run_id;
  std::vector<SlurmArray> arrays;
  std::string report_job;
  std::string toJson() const;
  static SlurmSubmission fromJson(const std::string& text, const std::string& where);
};

/// Submits the jobs in `todo` (ids; the order of the plan); throws std::runtime_error with sbatch's message.
SlurmSubmission submitToSlurm(const Plan& plan, const std::vector<std::string>& todo, const SlurmOptions& options);

/// The batch script of an array (what the tests check without a cluster).
std::string batchScript(const Plan& plan, const std::string& list_path, const std::string& plan_path,
                        const std::string& self_exe, const std::string& run_id, const std::string& log_dir,
                        unsigned cpus_per_task);

/// Splits an sbatch option string as a shell would split plain words and quotes ("--time=1:00 -p 'a b'").
std::vector<std::string> splitShellWords(const std::string& text);

/// The Slurm states of a submission's tasks: "<array>_<task>" or "<job>" -> state (PENDING, RUNNING, ...), from
/// squeue (finished tasks are not listed). Empty when squeue is not there.
std::map<std::string, std::string> slurmQueue(const SlurmSubmission& submission);

/// The latest submission to `out_dir`, if any (reads .suite/slurm/last).
bool readLastSubmission(const std::string& out_dir, SlurmSubmission& submission);

/// Runs a command and returns its stdout; `status` gets its exit code.
std::string captureCommand(const std::vector<std::string>& argv, int& status);

}  // namespace cosmo::suite
