#pragma once
// What the report shows of one finished dataset, read from its JRL: the paper's Fig. 1 statistics, the
// validation, and the back-end check (the labelled inliers solved from the initialization, ATE against the
// ground truth beside the initialization's).
#include <string>

#include "cosmo/suite/job_record.hpp"

namespace cosmo::suite {

/// Summarises `<folder>/<jrl>`; a dataset that cannot be read throws std::runtime_error naming the file. A solve
/// that cannot run (no labels, no ground truth) leaves the ATEs at -1 with the reason in solve_note.
DatasetSummary summariseDataset(const std::string& folder, const std::string& jrl, const std::string& name,
                                const std::string& comm);

}  // namespace cosmo::suite
