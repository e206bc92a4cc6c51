#pragma once
// The report's rows and the text of their cells, shared by its markdown and HTML forms (report.cpp).
#include <optional>
#include <string>
#include <vector>

#include "cosmo/suite/report.hpp"

namespace cosmo::suite::report_rows {

/// One dataset (a group's comm model) or one estimate.
struct Row {
  const ReportJob* job = nullptr;
  std::string name, comm;
  std::optional<DatasetSummary> summary;  ///< when the group's record has it
  std::optional<PaperRow> paper;
};

std::vector<Row> rows(const ReportInput& input);

/// Cells: ours, the paper's, and the difference ("" when either is missing).
struct Compared {
  std::string ours, paper, diff;
};
Compared duration(const Row& r);
Compared length(const Row& r);
Compared lc(const Row& r);
Compared irlc(const Row& r);
std::string solve(const Row& r);  ///< "0.089 m (init 0.688 m)"
std::string cost(const Row& r);   ///< "143 s wall, 76 s CPU, 291 MB"
std::string figurePath(const Row& r, bool png);  ///< relative to the output folder; "" when none

/// The variants' summary: per (label, comm) with more than one dataset, mean / min / max of a few figures.
struct VariantSummary {
  std::string label, comm;
  std::size_t datasets = 0;
  std::vector<std::pair<std::string, std::string>> cells;  ///< (what, "mean (min - max)")
};
std::vector<VariantSummary> variantSummaries(const std::vector<Row>& rows);

}  // namespace cosmo::suite::report_rows
