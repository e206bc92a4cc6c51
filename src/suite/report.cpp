#include "cosmo/suite/report.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosmo/comm/connectivity.hpp"
#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/common/whole_file.hpp"
#include "report_rows.hpp"
#include "report_table.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

using report_rows::Row;
using report_table::escapeHtml;
using report_table::Table;

std::string mdCell(const std::string& s) { return s.empty() ? "—" : s; }

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

/// The datasets table: one row per dataset (the first `count` rows), ours with the paper's in parentheses.
Table datasetsTable(const std::vector<Row>& rows, std::size_t count) {
  Table t{{"dataset", "status", "duration (paper)", "length (paper)", "LC (paper)", "IRLC (paper)",
           "inliers solve ATE (init)", "wall, CPU, peak memory"},
          {}};
  const auto both = [](const report_rows::Compared& c) {
    return mdCell(c.ours) + (c.paper.empty() ? "" : " (" + c.paper + ")");
  };
  for (std::size_t i = 0; i < rows.size() && i < count; ++i) {
    const Row& r = rows[i];
    t.rows.push_back({r.name, firstLine(r.job->status), both(report_rows::duration(r)), both(report_rows::length(r)),
                      both(report_rows::lc(r)), both(report_rows::irlc(r)), mdCell(report_rows::solve(r)),
                      mdCell(report_rows::cost(r))});
  }
  return t;
}

/// The per-dataset table (ours, the paper's, the difference).
Table datasetTable(const Row& r) {
  Table t{{"", "ours", "paper", "difference"}, {}};
  const std::vector<std::pair<std::string, report_rows::Compared>> lines{{"duration", report_rows::duration(r)},
                                                                         {"length", report_rows::length(r)},
                                                                         {"LC (outliers)", report_rows::lc(r)},
                                                                         {"IRLC (outliers)", report_rows::irlc(r)}};
  for (const auto& [what, c] : lines) t.rows.push_back({what, mdCell(c.ours), mdCell(c.paper), mdCell(c.diff)});
  t.rows.push_back({"inliers solve ATE (init)", mdCell(report_rows::solve(r)), "", ""});
  t.rows.push_back({"wall, CPU, peak memory", mdCell(report_rows::cost(r)), "", "the run of all comm models"});
  t.rows.push_back({"status", r.job->status, "", ""});
  return t;
}

std::string variantsSection(const std::vector<Row>& rows, bool html) {
  const auto sums = report_rows::variantSummaries(rows);
  if (sums.empty()) return "";
  Table t{{"sequence", "comm", "datasets"}, {}};
  for (const auto& [what, v] : sums.front().cells) t.header.push_back(what);
  for (const auto& s : sums) {
    std::vector<std::string> row{s.label, s.comm, std::to_string(s.datasets)};
    for (const auto& [what, v] : s.cells) row.push_back(v);
    t.rows.push_back(row);
  }
  const std::string intro = "Mean (min – max) over the datasets of each sequence and comm model.";
  if (html) return "<h2>Variants of one sequence</h2>\n<p>" + escapeHtml(intro) + "</p>\n" + report_table::html(t);
  return "## Variants of one sequence\n\n" + intro + "\n\n" + report_table::markdown(t) + "\n";
}

/// A dataset's radio connectivity (`<dataset>_connectivity.json` in its job's folder) and its timeline figure.
struct DatasetConnectivity {
  std::string name;
  comm::Connectivity connectivity;
  std::string svg, png;  ///< relative to the output folder; "" when absent
};

std::vector<DatasetConnectivity> connectivities(const ReportInput& input, const std::vector<Row>& rows) {
  std::vector<DatasetConnectivity> out;
  for (const Row& r : rows) {
    if (!r.summary || r.summary->jrl.empty()) continue;
    const fs::path folder = fs::path(r.job->job->id);
    const std::string jrl = (fs::path(input.out_dir) / folder / r.summary->jrl).string();
    const std::string json = comm::datasetConnectivityPath(jrl);
    if (!fs::exists(json)) continue;
    DatasetConnectivity d;
    d.name = r.name;
    try {
      d.connectivity = comm::Connectivity::read(json);
    } catch (const std::exception&) { continue; }  // unreadable: the dataset shows no connectivity
    const std::string stem = fs::path(r.summary->jrl).stem().string();
    const auto figure = [&](const std::string& ext) {
      const fs::path rel = folder / (stem + ".connectivity" + ext);
      return fs::exists(fs::path(input.out_dir) / rel) ? rel.string() : std::string();
    };
    d.svg = figure(".svg");
    d.png = figure(".png");
    out.push_back(d);
  }
  return out;
}

/// One row per robot pair of a dataset.
Table connectivityTable(const comm::Connectivity& c) {
  Table t{{"pair", "connected", "disconnections", "delivered / dropped", "throughput while connected", "bytes"}, {}};
  char buf[64];
  for (const comm::PairConnectivity& p : c.pairs) {
    std::snprintf(buf, sizeof buf, "%.1f %% (%.1f s)", 100.0 * c.connectedFraction(p), p.connected_s);
    std::string connected = buf;
    std::snprintf(buf, sizeof buf, "%.0f kB/s", p.throughputConnectedBps() / 1000.0);
    std::string throughput = buf;
    std::snprintf(buf, sizeof buf, "%.1f MB", p.bytes / 1e6);
    const std::string bytes = buf;
    const std::string ab = std::string(1, p.a) + "→" + p.b, ba = std::string(1, p.b) + "→" + p.a;
    t.rows.push_back({std::string(1, p.a) + "–" + p.b, connected, std::to_string(p.disconnections),
                      ab + " " + std::to_string(p.delivered_ab) + " / " + std::to_string(p.dropped_ab) + ", " + ba +
                          " " + std::to_string(p.delivered_ba) + " / " + std::to_string(p.dropped_ba),
                      throughput, bytes});
  }
  return t;
}

const char* kConnectivityIntro =
    "Per robot pair of each dataset's radio run (docs/design.md \"Connectivity\"): connected = both robots on and "
    "within d_init (inside a radio trace's window: the window's `connected`); the percentage is of the run; a "
    "disconnection is a connected step followed by one that is not; dropped = timed out.";

std::string connectivitySectionMarkdown(const std::vector<DatasetConnectivity>& cs) {
  if (cs.empty()) return "";
  std::string out = std::string("## Connectivity\n\n") + kConnectivityIntro + "\n\n";
  for (const auto& d : cs) {
    out += "### " + d.name + "\n\n";
    const std::string fig = d.png.empty() ? d.svg : d.png;
    if (!fig.empty()) out += "![" + d.name + " connectivity](" + fig + ")\n\n";
    out += report_table::markdown(connectivityTable(d.connectivity)) + "\n";
  }
  return out;
}

std::string base64(const std::string& data);

std::string connectivitySectionHtml(const ReportInput& input, const std::vector<DatasetConnectivity>& cs) {
  if (cs.empty()) return "";
  std::string out = "<h2>Connectivity</h2>\n<p>" + escapeHtml(kConnectivityIntro) + "</p>\n";
  for (const auto& d : cs) {
    out += "<div class=\"wide\"><h3>" + escapeHtml(d.name) + "</h3>";
    if (!d.svg.empty())
      out += "<img alt=\"" + escapeHtml(d.name) + " connectivity\" src=\"data:image/svg+xml;base64," +
             base64(readWholeFileOrEmpty((fs::path(input.out_dir) / d.svg).string())) + "\">";
    out += report_table::html(connectivityTable(d.connectivity)) + "</div>\n";
  }
  return out;
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

std::string figureCard(const ReportInput& input, const Row& r) {
  std::string img;
  const std::string svg = report_rows::figurePath(r, false);
  if (!svg.empty())
    img = "<img alt=\"" + escapeHtml(r.name) + "\" src=\"data:image/svg+xml;base64," +
          base64(readWholeFileOrEmpty((fs::path(input.out_dir) / svg).string())) + "\">";
  else
    img = "<div class=\"nofig\">no figure</div>";
  return "<div class=\"card\"><h3>" + escapeHtml(r.name) + "</h3>" + img + report_table::html(datasetTable(r)) +
         "</div>\n";
}

}  // namespace

std::string reportTableHead(const ReportInput& input, std::size_t rows) {
  return report_table::markdown(datasetsTable(report_rows::rows(input), rows));
}

std::string reportMarkdown(const ReportInput& input) {
  const auto rows = report_rows::rows(input);
  std::ostringstream out;
  out << "# Suite " << input.suite_name << "\n\n`" << input.suite_path << "` → `" << input.out_dir << "`. "
      << input.note << " Paper values: the COSMO-Bench paper's Fig. 1 (config/paper/fig1.yaml); the "
      << "wall and CPU time and peak memory are those of the run that made a group (its comm models share one "
      << "odometry pass).\n\n## Datasets\n\n"
      << report_table::markdown(datasetsTable(rows, rows.size())) << "\n## Figures\n\n| | |\n|---|---|\n";
  std::vector<std::string> cells;
  for (const auto& r : rows) {
    const std::string fig = report_rows::figurePath(r, true);
    if (!fig.empty()) cells.push_back("![" + r.name + "](" + fig + ")<br>" + r.name);
  }
  for (std::size_t i = 0; i < cells.size(); i += 2)
    out << "| " << cells[i] << " | " << (i + 1 < cells.size() ? cells[i + 1] : "") << " |\n";
  out << "\n## Per dataset\n\n";
  for (const auto& r : rows)
    if (!r.comm.empty()) out << "### " << r.name << "\n\n" << report_table::markdown(datasetTable(r)) << "\n";
  out << variantsSection(rows, false) << connectivitySectionMarkdown(connectivities(input, rows));
  return out.str();
}

std::string reportHtml(const ReportInput& input) {
  const auto rows = report_rows::rows(input);
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Suite " << escapeHtml(input.suite_name)
      << "</title>\n<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse;font-size:"
         "0.85em}td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}.grid{display:grid;grid-template-"
         "columns:repeat(auto-fill,minmax(420px,1fr));gap:1em}.card img{width:100%;background:#fff}.card h3{"
         "margin:0.2em 0}.wide img{width:100%;max-width:1500px;background:#fff}</style></head><body>\n<h1>Suite "
      << escapeHtml(input.suite_name) << "</h1>\n<p><code>" << escapeHtml(input.suite_path) << "</code> → <code>"
      << escapeHtml(input.out_dir) << "</code>. " << escapeHtml(input.note)
      << " Paper values: the COSMO-Bench paper's Fig. 1 (config/paper/fig1.yaml).</p>\n<h2>Datasets</h2>\n";
  out << report_table::html(datasetsTable(rows, rows.size())) << "<h2>Figures</h2>\n<div class=\"grid\">\n";
  for (const auto& r : rows)
    if (!r.comm.empty()) out << figureCard(input, r);
  out << "</div>\n"
      << variantsSection(rows, true) << connectivitySectionHtml(input, connectivities(input, rows))
      << "</body></html>\n";
  return out.str();
}

std::vector<std::string> writeReport(const ReportInput& input) {
  const std::string md = (fs::path(input.out_dir) / "report.md").string();
  const std::string html = (fs::path(input.out_dir) / "report.html").string();
  dataset::writeFileAtomically(md, reportMarkdown(input));
  dataset::writeFileAtomically(html, reportHtml(input));
  return {md, html};
}

}  // namespace cosmo::suite
