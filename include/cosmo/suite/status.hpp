#pragma once
// What each job of a plan is now, read from the output folder (records, failure records, locks) and, after a
// Slurm submission, the queue: for `cosmo_suite status`, the report a Slurm run writes at its end, and the report's
// input.
#include <string>

#include "cosmo/suite/local_run.hpp"
#include "cosmo/suite/paper_table.hpp"
#include "cosmo/suite/report.hpp"

namespace cosmo::suite {

/// Each job's status: "done" (current, made by run `run_id`, or any run when `run_id` is empty), "skipped as current" (current, made by another
/// run), "failed: <reason>" (a failure record of `run_id`, or of any run when `run_id` is empty), "running"
/// (its lock is held), "queued in Slurm (<state>)", "stale: <why>", "missing".
JobStatuses folderStatuses(const Plan& plan, const std::string& run_id);

/// The report's input: every job with its status and, when current, its record.
ReportInput reportInput(const Plan& plan, const JobStatuses& statuses, const PaperTable* paper,
                        const std::string& note);

/// "8 datasets: 6 done, 2 skipped as current, 0 failed" from the statuses.
std::string statusCounts(const Plan& plan, const JobStatuses& statuses);

}  // namespace cosmo::suite
