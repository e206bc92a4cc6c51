#pragma once
// The suite's report, <out>/report.md and a self-contained <out>/report.html (figures inline): every dataset's
// trajectory figure in a grid (the paper's Fig. 1 style: the figure and its table), one table per dataset with
// ours beside the paper's Fig. 1 values and the difference (duration, length, LC and IRLC counts and outlier %),
// the inlier solve's ATE beside the initialization's, wall and CPU time and peak memory of the run, and the
// status; the variants of one sequence summarised (mean, min, max).
#include <optional>
#include <string>
#include <vector>

#include "cosmo/suite/job_record.hpp"
#include "cosmo/suite/paper_table.hpp"
#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

struct ReportJob {
  const Job* job = nullptr;
  std::optional<JobRecord> record;  ///< its folder's record, when it has a current one
  /// "done", "skipped as current", "failed: <reason>", "not run: <why>", "stale: <why>", "missing", ...
  std::string status;
};

struct ReportInput {
  std::string suite_name, suite_path, out_dir;
  std::string note;  ///< a line under the title (e.g. the run's counts)
  std::vector<ReportJob> jobs;
  const PaperTable* paper = nullptr;
};

std::string reportMarkdown(const ReportInput& input);
std::string reportHtml(const ReportInput& input);

/// Writes both into the output folder (atomically); returns their paths.
std::vector<std::string> writeReport(const ReportInput& input);

/// The first `rows` rows of the markdown's dataset table (for printing after a run).
std::string reportTableHead(const ReportInput& input, std::size_t rows);

}  // namespace cosmo::suite
