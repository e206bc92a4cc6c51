#pragma once
// One job of a plan, start to end, as a local run and a Slurm task both run it (`cosmo_suite job`): under the job's
// lock, skip it when its folder is current; else run cosmo_generate into a fresh tmp folder (its output in
// .suite/logs/<job>.log), run the variants' steps on each JRL, summarise each dataset, hash every output, write
// the record, and move the folder into place. A failure leaves the job's previous folder as it was and writes
// .suite/failed/<job>.json with the reason.
#include <string>

#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

enum class JobOutcome { Done, Current, Failed };

struct RunJobOptions {
  unsigned registration_threads = 1;  ///< cosmo_generate --registration-threads
  std::string run_id;                 ///< written into the record: which run made the folder
};

/// Runs `job_id` of `plan`. Never throws: anything that goes wrong is a failure with its reason on record.
JobOutcome runJob(const Plan& plan, const std::string& job_id, const RunJobOptions& options);

/// The log of a job's last run, .suite/logs/<job>.log.
std::string jobLogPath(const std::string& out_dir, const std::string& job_id);
/// The failure record of a job, .suite/failed/<job>.json.
std::string jobFailurePath(const std::string& out_dir, const std::string& job_id);
/// The reason a failure record gives ("" when there is none).
std::string readFailure(const std::string& out_dir, const std::string& job_id, std::string* run_id = nullptr);

/// Exit codes of `cosmo_suite job`.
inline constexpr int kExitDone = 0, kExitFailed = 1, kExitCurrent = 3;

}  // namespace cosmo::suite
