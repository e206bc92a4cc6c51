#include "cosmo/suite/progress.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <sstream>

namespace cosmo::suite {

LogProgress readLogProgress(const std::string& log_text) {
  static const std::regex line(R"(^\[([A-Za-z0-9_.-]+)\]\s+([0-9.]+) / ([0-9.]+) s)");
  std::map<std::string, double> last;
  LogProgress p;
  std::istringstream in(log_text);
  std::string l;
  std::smatch m;
  while (std::getline(in, l))
    if (std::regex_search(l, m, line)) {
      last[m[1]] = std::stod(m[2]);
      p.length_s = std::stod(m[3]);
    }
  for (const auto& [comm, t] : last) p.done_s += t;
  return p;
}

std::string formatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[48];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld s", s);
  return buf;
}

std::string progressLine(const ProgressCounts& c) {
  std::ostringstream out;
  out << "[suite] " << c.done << " done, " << c.skipped << " skipped as current, " << c.failed << " failed, "
      << c.running << " running, " << c.left << " left";
  if (c.running + c.left > 0) {
    out << "; " << std::lround(c.remaining_s) << " s of sequence to process";
    if (c.processed_s >= kEtaAfterShare * (c.processed_s + c.remaining_s) && c.processed_s > 0.0 && c.elapsed_s > 0.0)
      out << ", ETA " << formatDuration(c.remaining_s / (c.processed_s / c.elapsed_s));
  }
  return out.str();
}

}  // namespace cosmo::suite
