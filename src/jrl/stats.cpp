#include "cosmo/jrl/stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

namespace cosmo::jrl {

long DatasetStats::durationRoundedS() const { return std::lround(duration_s); }

DatasetStats computeStats(const Dataset& d) {
  DatasetStats s;
  s.name = d.name;
  s.robots = d.robots;
  StampNs first = std::numeric_limits<StampNs>::max(), last = 0;
  for (char r : d.robots) {
    const auto it = d.measurements.find(r);
    if (it == d.measurements.end()) continue;
    const std::set<FactorId>* outliers = nullptr;
    if (d.outliers) {
      const auto o = d.outliers->find(r);
      if (o != d.outliers->end()) outliers = &o->second;
    }
    const auto& entries = it->second;
    s.entries += entries.size();
    for (std::size_t e = 0; e < entries.size(); ++e) {
      first = std::min(first, entries[e].stamp);
      last = std::max(last, entries[e].stamp);
      for (std::size_t m = 0; m < entries[e].factors.size(); ++m) {
        const Factor& f = entries[e].factors[m];
        ++s.factors;
        if (isPrior(f.type)) ++s.priors;
        if (!f.isBetweenPose3() || f.keys.size() != 2) continue;
        const Key k1 = f.keys[0], k2 = f.keys[1];
        const bool outlier = outliers && outliers->count(FactorId{e, m});
        if (robotOf(k1) != robotOf(k2)) {
          ++s.irlc_count;
          s.irlc_outliers += outlier ? 1 : 0;
        } else if (indexOf(k2) == indexOf(k1) + 1) {
          ++s.odometry;
        } else {
          ++s.lc_count;
          s.lc_outliers += outlier ? 1 : 0;
        }
      }
    }
  }
  if (s.entries > 0) {
    s.first_stamp = first;
    s.last_stamp = last;
    s.duration_s = static_cast<double>(last - first) * 1e-9;
  }
  s.has_outlier_labels = d.outliers.has_value();
  if (d.groundtruth) {
    s.has_groundtruth = true;
    for (char r : d.robots) {
      const auto it = d.groundtruth->find(r);
      if (it == d.groundtruth->end()) continue;
      // Values are key-sorted, so own poses come in index order.
      const Eigen::Vector3d* prev = nullptr;
      for (const auto& [key, v] : it->second) {
        const auto* p = std::get_if<Pose3Value>(&v);
        if (robotOf(key) != r || !p) continue;
        if (prev) s.length_m += (p->translation - *prev).norm();
        prev = &p->translation;
      }
    }
  }
  return s;
}

std::string formatDuration(double seconds) {
  const long total = std::max(0L, std::lround(seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld", total / 60, total % 60);
  return buf;
}

namespace {
std::string robotList(const std::vector<char>& robots) {
  std::string s;
  for (char r : robots) {
    if (!s.empty()) s += ' ';
    s += r;
  }
  return s;
}

std::string closures(std::size_t count, std::size_t outliers, double pct, bool labelled) {
  char buf[96];
  if (!labelled)
    std::snprintf(buf, sizeof buf, "%zu (no outlier labels)", count);
  else
    std::snprintf(buf, sizeof buf, "%zu (%.1f %%), %zu outliers", count, pct, outliers);
  return buf;
}
}  // namespace

std::string formatStats(const DatasetStats& s) {
  char length[64];
  if (s.has_groundtruth)
    std::snprintf(length, sizeof length, "%.2f km", s.length_m / 1000.0);
  else
    std::snprintf(length, sizeof length, "n/a (no groundtruth)");
  std::string out = s.name + "\n";
  out += "  robots    " + robotList(s.robots) + "\n";
  out += "  duration  " + formatDuration(s.duration_s) + "\n";
  out += "  length    " + std::string(length) + "\n";
  out += "  LC        " + closures(s.lc_count, s.lc_outliers, s.lcOutlierPercent(), s.has_outlier_labels) + "\n";
  out += "  IRLC      " + closures(s.irlc_count, s.irlc_outliers, s.irlcOutlierPercent(), s.has_outlier_labels) + "\n";
  out += "  entries   " + std::to_string(s.entries) + ", factors " + std::to_string(s.factors) + " (" +
         std::to_string(s.priors) + " priors, " + std::to_string(s.odometry) + " odometry)\n";
  return out;
}

std::string statsJson(const DatasetStats& s) {
  auto round = [](double v, double scale) { return std::round(v * scale) / scale; };
  nlohmann::json j;
  j["name"] = s.name;
  j["robots"] = nlohmann::json::array();
  for (char r : s.robots) j["robots"].push_back(std::string(1, r));
  j["entries"] = s.entries;
  j["factors"] = s.factors;
  j["priors"] = s.priors;
  j["odometry"] = s.odometry;
  j["duration_s"] = s.durationRoundedS();
  j["duration"] = formatDuration(s.duration_s);
  j["duration_exact_s"] = round(s.duration_s, 1e3);
  j["length_m"] = round(s.length_m, 1e2);
  j["lc_count"] = s.lc_count;
  j["lc_outliers"] = s.lc_outliers;
  j["lc_outlier_pct"] = round(s.lcOutlierPercent(), 1e2);
  j["irlc_count"] = s.irlc_count;
  j["irlc_outliers"] = s.irlc_outliers;
  j["irlc_outlier_pct"] = round(s.irlcOutlierPercent(), 1e2);
  j["has_groundtruth"] = s.has_groundtruth;
  j["has_outlier_labels"] = s.has_outlier_labels;
  return j.dump();
}

}  // namespace cosmo::jrl
