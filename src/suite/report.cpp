#include "cosmo/suite/report.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosmo/dataset/atomic_file.hpp"
#include "report_rows.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

using report_rows::Row;

std::string mdCell(const std::string& s) { return s.empty() ? "—" : s; }

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

std::string tableHeader() {
  return "| dataset | status | duration (paper) | length (paper) | LC (paper) | IRLC (paper) | inliers solve ATE "
         "(init) | wall, CPU, peak memory |\n|---|---|---|---|---|---|---|---|\n";
}

std::string tableRow(const Row& r) {
  const auto both = [](const report_rows::Compared& c) {
    return mdCell(c.ours) + (c.paper.empty() ? "" : " (" + c.paper + ")");
  };
  return "| " + r.name + " | " + firstLine(r.job->status) + " | " + both(report_rows::duration(r)) + " | " +
         both(report_rows::length(r)) + " | " + both(report_rows::lc(r)) + " | " + both(report_rows::irlc(r)) + " | " +
         mdCell(report_rows::solve(r)) + " | " + mdCell(report_rows::cost(r)) + " |\n";
}

/// The per-dataset table (ours, the paper's, the difference), in markdown.
std::string datasetTable(const Row& r) {
  std::ostringstream out;
  out << "| | ours | paper | difference |\n|---|---|---|---|\n";
  const std::vector<std::pair<std::string, report_rows::Compared>> lines{{"duration", report_rows::duration(r)},
                                                                          {"length", report_rows::length(r)},
                                                                          {"LC (outliers)", report_rows::lc(r)},
                                                                          {"IRLC (outliers)", report_rows::irlc(r)}};
  for (const auto& [what, c] : lines)
    out << "| " << what << " | " << mdCell(c.ours) << " | " << mdCell(c.paper) << " | " << mdCell(c.diff) << " |\n";
  out << "| inliers solve ATE (init) | " << mdCell(report_rows::solve(r)) << " | | |\n";
  out << "| wall, CPU, peak memory | " << mdCell(report_rows::cost(r)) << " | | the run of all comm models |\n";
  out << "| status | " << r.job->status << " | | |\n";
  return out.str();
}

std::string variantsSection(const std::vector<Row>& rows, bool html) {
  const auto sums = report_rows::variantSummaries(rows);
  if (sums.empty()) return "";
  std::ostringstream out;
  out << (html ? "<h2>Variants of one sequence</h2>\n" : "## Variants of one sequence\n\n")
      << (html ? "<p>" : "") << "Mean (min – max) over the datasets of each sequence and comm model."
      << (html ? "</p>\n<table><tr><th>sequence</th><th>comm</th><th>datasets</th>" : "\n\n| sequence | comm | datasets |");
  for (const auto& [what, v] : sums.front().cells) out << (html ? "<th>" + what + "</th>" : " " + what + " |");
  out << (html ? "</tr>\n" : "\n|---|---|---|");
  if (!html)
    for (std::size_t i = 0; i < sums.front().cells.size(); ++i) out << "---|";
  if (!html) out << "\n";
  for (const auto& s : sums) {
    out << (html ? "<tr><td>" : "| ") << s.label << (html ? "</td><td>" : " | ") << s.comm << (html ? "</td><td>" : " | ")
        << s.datasets << (html ? "</td>" : " |");
    for (const auto& [what, v] : s.cells) out << (html ? "<td>" + v + "</td>" : " " + v + " |");
    out << (html ? "</tr>\n" : "\n");
  }
  out << (html ? "</table>\n" : "\n");
  return out.str();
}

std::string escapeHtml(const std::string& s) {
  std::string o;
  for (const char c : s) o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return o;
}

std::string base64(const std::string& data) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < data.size(); i += 3) {
    const unsigned v = (unsigned char)data[i] << 16 | (unsigned char)data[i + 1] << 8 | (unsigned char)data[i + 2];
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (i + 1 == data.size()) {
    const unsigned v = (unsigned char)data[i] << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == data.size()) {
    const unsigned v = (unsigned char)data[i] << 16 | (unsigned char)data[i + 1] << 8;
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The markdown table as HTML (the per-dataset tables are small markdown tables).
std::string tableHtml(const std::string& md) {
  std::istringstream in(md);
  std::string line, out = "<table>\n";
  bool head = true;
  while (std::getline(in, line)) {
    if (line.rfind("|---", 0) == 0) continue;
    out += "<tr>";
    std::size_t a = 1, b;
    while ((b = line.find(" |", a)) != std::string::npos) {
      const std::string cell = line.substr(a + 1, b - a - 1);
      out += (head ? "<th>" : "<td>") + escapeHtml(cell) + (head ? "</th>" : "</td>");
      a = b + 2;
    }
    out += "</tr>\n";
    head = false;
  }
  return out + "</table>\n";
}

std::string figureCard(const ReportInput& input, const Row& r) {
  std::string img;
  const std::string svg = report_rows::figurePath(r, false);
  if (!svg.empty())
    img = "<img alt=\"" + escapeHtml(r.name) + "\" src=\"data:image/svg+xml;base64," +
          base64(readFile((fs::path(input.out_dir) / svg).string())) + "\">";
  else
    img = "<div class=\"nofig\">no figure</div>";
  return "<div class=\"card\"><h3>" + escapeHtml(r.name) + "</h3>" + img + tableHtml(datasetTable(r)) + "</div>\n";
}

}  // namespace

std::string reportTableHead(const ReportInput& input, std::size_t rows) {
  std::string out = tableHeader();
  const auto all = report_rows::rows(input);
  for (std::size_t i = 0; i < all.size() && i < rows; ++i) out += tableRow(all[i]);
  return out;
}

std::string reportMarkdown(const ReportInput& input) {
  const auto rows = report_rows::rows(input);
  std::ostringstream out;
  out << "# Suite " << input.suite_name << "\n\n`" << input.suite_path << "` → `" << input.out_dir << "`. "
      << input.note << " Paper values: the COSMO-Bench paper's Fig. 1 (config/paper/fig1.yaml); the "
      << "wall and CPU time and peak memory are those of the run that made a group (its comm models share one "
      << "odometry pass).\n\n## Datasets\n\n"
      << tableHeader();
  for (const auto& r : rows) out << tableRow(r);
  out << "\n## Figures\n\n| | |\n|---|---|\n";
  std::vector<std::string> cells;
  for (const auto& r : rows) {
    const std::string fig = report_rows::figurePath(r, true);
    if (!fig.empty()) cells.push_back("![" + r.name + "](" + fig + ")<br>" + r.name);
  }
  for (std::size_t i = 0; i < cells.size(); i += 2)
    out << "| " << cells[i] << " | " << (i + 1 < cells.size() ? cells[i + 1] : "") << " |\n";
  out << "\n## Per dataset\n\n";
  for (const auto& r : rows)
    if (!r.comm.empty()) out << "### " << r.name << "\n\n" << datasetTable(r) << "\n";
  out << variantsSection(rows, false);
  return out.str();
}

std::string reportHtml(const ReportInput& input) {
  const auto rows = report_rows::rows(input);
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Suite " << escapeHtml(input.suite_name)
      << "</title>\n<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse;font-size:"
         "0.85em}td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}.grid{display:grid;grid-template-"
         "columns:repeat(auto-fill,minmax(420px,1fr));gap:1em}.card img{width:100%;background:#fff}.card h3{"
         "margin:0.2em 0}</style></head><body>\n<h1>Suite "
      << escapeHtml(input.suite_name) << "</h1>\n<p><code>" << escapeHtml(input.suite_path) << "</code> → <code>"
      << escapeHtml(input.out_dir) << "</code>. " << escapeHtml(input.note)
      << " Paper values: the COSMO-Bench paper's Fig. 1 (config/paper/fig1.yaml).</p>\n<h2>Datasets</h2>\n";
  std::string md = tableHeader();
  for (const auto& r : rows) md += tableRow(r);
  out << tableHtml(md) << "<h2>Figures</h2>\n<div class=\"grid\">\n";
  for (const auto& r : rows)
    if (!r.comm.empty()) out << figureCard(input, r);
  out << "</div>\n" << variantsSection(rows, true) << "</body></html>\n";
  return out.str();
}

std::vector<std::string> writeReport(const ReportInput& input) {
  const std::string md = (fs::path(input.out_dir) / "report.md").string();
  const std::string html = (fs::path(input.out_dir) / "report.html").string();
  writeFileAtomically(md, reportMarkdown(input));
  writeFileAtomically(html, reportHtml(input));
  return {md, html};
}

}  // namespace cosmo::suite
