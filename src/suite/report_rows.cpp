#include "report_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>

#include "cosmo/jrl/stats.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite::report_rows {
namespace {

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string signedDuration(double seconds) {
  const long s = std::lround(seconds);
  return std::string(s < 0 ? "-" : "+") + jrl::formatDuration(std::abs(static_cast<double>(s)));
}

double pct(std::size_t outliers, std::size_t count) { return count ? 100.0 * double(outliers) / double(count) : 0.0; }

std::string countPct(std::size_t count, double percent) {
  return std::to_string(count) + " (" + format("%.1f", percent) + " %)";
}

std::string countDiff(std::size_t ours, double ours_pct, std::size_t paper, double paper_pct) {
  const long d = static_cast<long>(ours) - static_cast<long>(paper);
  return (d >= 0 ? "+" : "") + std::to_string(d) + " (" + format("%+.1f", ours_pct - paper_pct) + " pt)";
}

}  // namespace

std::vector<Row> rows(const ReportInput& input) {
  std::vector<Row> out;
  for (const auto& rj : input.jobs) {
    if (rj.job->kind == Job::Kind::Estimate) {
      out.push_back({&rj, rj.job->id, "", std::nullopt, std::nullopt});
      continue;
    }
    const auto names = rj.job->datasetNames();
    for (std::size_t i = 0; i < names.size(); ++i) {
      Row r{&rj, names[i], rj.job->comms[i], std::nullopt, std::nullopt};
      if (rj.record)
        for (const auto& d : rj.record->datasets)
          if (d.comm == r.comm) r.summary = d;
      if (input.paper) r.paper = input.paper->find(rj.job->sequence_name);
      out.push_back(r);
    }
  }
  return out;
}

Compared duration(const Row& r) {
  Compared c;
  if (r.summary) c.ours = jrl::formatDuration(r.summary->duration_s);
  if (r.paper) c.paper = jrl::formatDuration(r.paper->duration_s);
  if (r.summary && r.paper) c.diff = signedDuration(std::round(r.summary->duration_s) - r.paper->duration_s);
  return c;
}

Compared length(const Row& r) {
  Compared c;
  if (r.summary) c.ours = format("%.2f km", r.summary->length_m / 1000.0);
  if (r.paper) c.paper = format("%.2f km", r.paper->length_m / 1000.0);
  if (r.summary && r.paper) c.diff = format("%+.2f km", (r.summary->length_m - r.paper->length_m) / 1000.0);
  return c;
}

Compared lc(const Row& r) {
  Compared c;
  if (r.summary) c.ours = countPct(r.summary->lc, pct(r.summary->lc_outliers, r.summary->lc));
  if (r.paper) c.paper = countPct(r.paper->lc, r.paper->lc_pct);
  if (r.summary && r.paper)
    c.diff = countDiff(r.summary->lc, pct(r.summary->lc_outliers, r.summary->lc), r.paper->lc, r.paper->lc_pct);
  return c;
}

Compared irlc(const Row& r) {
  Compared c;
  if (r.summary) c.ours = countPct(r.summary->irlc, pct(r.summary->irlc_outliers, r.summary->irlc));
  const bool paper = r.paper && r.paper->irlc.count(r.comm);
  if (paper) c.paper = countPct(r.paper->irlc.at(r.comm).first, r.paper->irlc.at(r.comm).second);
  if (r.summary && paper)
    c.diff = countDiff(r.summary->irlc, pct(r.summary->irlc_outliers, r.summary->irlc), r.paper->irlc.at(r.comm).first,
                       r.paper->irlc.at(r.comm).second);
  return c;
}

std::string solve(const Row& r) {
  if (!r.summary) return "";
  if (r.summary->inliers_ate_m < 0) return "(" + r.summary->solve_note + ")";
  return format("%.3f m", r.summary->inliers_ate_m) + " (init " + format("%.3f m", r.summary->init_ate_m) + ")";
}

std::string cost(const Row& r) {
  if (!r.job->record) return "";
  const JobRecord& rec = *r.job->record;
  return format("%.0f s wall, ", rec.wall_s) + format("%.0f s CPU, ", rec.cpu_s) + format("%.0f MB", rec.peak_rss_mb);
}

std::string figurePath(const Row& r, bool png) {
  if (!r.summary || r.summary->figure.empty()) return "";
  std::string file = r.summary->figure;
  if (png) {
    const std::string p = file.substr(0, file.size() - 4) + ".png";
    if (std::any_of(r.job->record->outputs.begin(), r.job->record->outputs.end(),
                    [&](const OutputFile& o) { return o.file == p; }))
      file = p;
  }
  return (fs::path(r.job->job->id) / file).string();
}

std::vector<VariantSummary> variantSummaries(const std::vector<Row>& rows) {
  std::map<std::pair<std::string, std::string>, std::vector<const DatasetSummary*>> groups;
  std::vector<std::pair<std::string, std::string>> order;
  for (const auto& r : rows) {
    if (!r.summary) continue;
    const auto key = std::make_pair(r.job->job->label, r.comm);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&*r.summary);
  }
  using Get = std::function<double(const DatasetSummary&)>;
  const std::vector<std::tuple<std::string, Get, const char*>> figures{
      {"LC", [](const DatasetSummary& d) { return double(d.lc); }, "%.1f"},
      {"LC outliers %", [](const DatasetSummary& d) { return pct(d.lc_outliers, d.lc); }, "%.1f"},
      {"IRLC", [](const DatasetSummary& d) { return double(d.irlc); }, "%.1f"},
      {"IRLC outliers %", [](const DatasetSummary& d) { return pct(d.irlc_outliers, d.irlc); }, "%.1f"},
      {"inliers ATE m", [](const DatasetSummary& d) { return d.inliers_ate_m; }, "%.3f"}};
  std::vector<VariantSummary> out;
  for (const auto& key : order) {
    const auto& ds = groups[key];
    if (ds.size() < 2) continue;
    VariantSummary s{key.first, key.second, ds.size(), {}};
    for (const auto& [what, get, f] : figures) {
      double sum = 0.0, lo = 1e300, hi = -1e300;
      std::size_t n = 0;
      for (const auto* d : ds) {
        const double v = get(*d);
        if (v < 0) continue;  // no solve
        sum += v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        ++n;
      }
      s.cells.emplace_back(what, n == 0 ? "—"
                                        : format(f, sum / double(n)) + " (" + format(f, lo) + " – " + format(f, hi) + ")");
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace cosmo::suite::report_rows
