#pragma once
// A table of the report: header cells and rows of cells, plain text, written once as markdown (report.md) and once
// as HTML (report.html) from the same cells (report.cpp).
#include <string>
#include <vector>

namespace cosmo::suite::report_table {

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  ///< as many cells each as the header
};

/// "| a | b |\n|---|---|\n| 1 | 2 |\n": an empty cell as "| |", '|' in a cell as "\|", a line break as <br>.
/// Throws std::logic_error when a row's cell count differs from the header's.
std::string markdown(const Table& table);

/// "<table>\n<tr><th>a</th><th>b</th></tr>\n<tr><td>1</td><td>2</td></tr>\n</table>\n": cells escaped
/// (escapeHtml), a line break as <br>. Throws std::logic_error like markdown().
std::string html(const Table& table);

/// &, <, > and " as character references.
std::string escapeHtml(const std::string& s);

}  // namespace cosmo::suite::report_table
