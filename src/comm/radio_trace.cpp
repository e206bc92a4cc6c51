#include "cosmo/comm/radio_trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cosmo::comm {

namespace {

const char* kHeader = "robot_a,robot_b,start,duration,throughput_Bps,latency,connected";

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

class RowError {
 public:
  RowError(std::string source, std::size_t line) : where_(std::move(source) + ":" + std::to_string(line) + ": ") {}
  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(where_ + what); }
  double number(const std::string& cell, const char* column) const {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(cell, &used);
    } catch (const std::exception&) { used = 0; }
    if (used == 0 || used != cell.size() || !std::isfinite(v))
      fail(std::string(column) + ": '" + cell + "' is not a finite number");
    return v;
  }
  char robot(const std::string& cell, const char* column) const {
    if (cell.size() != 1) fail(std::string(column) + ": '" + cell + "' is not a one-character robot id");
    return cell[0];
  }

 private:
  std::string where_;
};

TraceWindow parseRow(const std::vector<std::string>& cells, const RowError& at, std::size_t line) {
  if (cells.size() != 7) at.fail("expected 7 columns (" + std::string(kHeader) + "), got " + std::to_string(cells.size()));
  TraceWindow w;
  w.line = line;
  char a = at.robot(cells[0], "robot_a"), b = at.robot(cells[1], "robot_b");
  if (a == b) at.fail(std::string("robot_a and robot_b are both '") + a + "'");
  w.robot_a = std::min(a, b);
  w.robot_b = std::max(a, b);
  w.start = at.number(cells[2], "start");
  w.duration = at.number(cells[3], "duration");
  w.throughput_Bps = at.number(cells[4], "throughput_Bps");
  w.latency = at.number(cells[5], "latency");
  if (!(w.duration > 0.0)) at.fail("duration must be > 0, got " + cells[3]);
  if (w.throughput_Bps < 0.0) at.fail("throughput_Bps must be >= 0, got " + cells[4]);
  if (w.latency < 0.0) at.fail("latency must be >= 0, got " + cells[5]);
  if (cells[6] != "0" && cells[6] != "1") at.fail("connected must be 0 or 1, got '" + cells[6] + "'");
  w.connected = cells[6] == "1";
  return w;
}

std::string pairName(char a, char b) { return std::string(1, a) + "-" + std::string(1, b); }

}  // namespace

RadioTrace RadioTrace::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the radio trace");
  return parse(in, path);
}

RadioTrace RadioTrace::parse(std::istream& in, const std::string& source) {
  RadioTrace t;
  t.source_ = source;
  std::string line;
  std::size_t number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    const RowError at(source, number);
    if (!header) {
      if (s != kHeader) at.fail("expected the header '" + std::string(kHeader) + "', got '" + s + "'");
      header = true;
      continue;
    }
    TraceWindow w = parseRow(splitCsv(s), at, number);
    try {
      t.add(w);
    } catch (const std::runtime_error& e) { at.fail(e.what()); }
  }
  if (!header) throw std::runtime_error(source + ": no header line '" + std::string(kHeader) + "'");
  return t;
}

void RadioTrace::add(TraceWindow w) {
  auto& list = pairs_[{w.robot_a, w.robot_b}];
  const auto it = std::upper_bound(list.begin(), list.end(), w.start,
                                   [](double s, const TraceWindow& x) { return s < x.start; });
  const double eps = 1e-6;  // s: rounding of written times, far below any window
  const auto overlap = [&](const TraceWindow& o) {
    return "window [" + std::to_string(w.start) + ", " + std::to_string(w.end()) + ") of " +
           pairName(w.robot_a, w.robot_b) + " overlaps [" + std::to_string(o.start) + ", " + std::to_string(o.end()) +
           ")" + (o.line ? " at line " + std::to_string(o.line) : std::string());
  };
  if (it != list.begin() && std::prev(it)->end() > w.start + eps) throw std::runtime_error(overlap(*std::prev(it)));
  if (it != list.end() && w.end() > it->start + eps) throw std::runtime_error(overlap(*it));
  list.insert(it, w);
}

RadioTrace RadioTrace::fromRecords(const std::vector<LinkRecord>& records, double step, double origin) {
  std::map<std::pair<char, char>, std::vector<LinkRecord>> by_pair;
  for (const LinkRecord& r : records) by_pair[{r.robot_a, r.robot_b}].push_back(r);
  RadioTrace t;
  t.source_ = "<recorded>";
  for (auto& [pair, list] : by_pair) {
    std::stable_sort(list.begin(), list.end(),
                     [](const LinkRecord& x, const LinkRecord& y) { return x.step_time < y.step_time; });
    auto& windows = t.pairs_[pair];
    for (const LinkRecord& r : list) {
      const double start = r.step_time - step - origin;
      if (!windows.empty()) {
        TraceWindow& last = windows.back();
        const bool contiguous = std::abs(last.end() - start) <= 1e-6 * step;
        if (contiguous && last.connected == r.connected && last.throughput_Bps == r.throughput_Bps &&
            last.latency == r.latency) {
          last.duration = r.step_time - origin - last.start;
          continue;
        }
      }
      TraceWindow w;
      w.robot_a = pair.first;
      w.robot_b = pair.second;
      w.start = start;
      w.duration = step;
      w.throughput_Bps = r.throughput_Bps;
      w.latency = r.latency;
      w.connected = r.connected;
      windows.push_back(w);
    }
  }
  return t;
}

void RadioTrace::checkTeam(const std::vector<char>& team) const {
  std::string names;
  for (char r : team) names += (names.empty() ? "" : ", ") + std::string(1, r);
  for (const auto& [pair, list] : pairs_)
    for (char r : {pair.first, pair.second})
      if (std::find(team.begin(), team.end(), r) == team.end()) {
        std::size_t line = list.front().line;  // the pair's first row in the file
        for (const TraceWindow& w : list) line = std::min(line, w.line);
        throw std::runtime_error(source_ + ":" + std::to_string(line) + ": robot '" + std::string(1, r) +
                                 "' is not in the team (" + names + ")");
      }
}

const TraceWindow* RadioTrace::find(char a, char b, double t) const {
  const auto it = pairs_.find({std::min(a, b), std::max(a, b)});
  if (it == pairs_.end()) return nullptr;
  const auto& list = it->second;
  auto w = std::upper_bound(list.begin(), list.end(), t, [](double s, const TraceWindow& x) { return s < x.start; });
  if (w == list.begin()) return nullptr;
  --w;
  return t < w->end() ? &*w : nullptr;
}

std::size_t RadioTrace::windowCount() const {
  std::size_t n = 0;
  for (const auto& [pair, list] : pairs_) n += list.size();
  return n;
}

std::vector<TraceWindow> RadioTrace::windows() const {
  std::vector<TraceWindow> out;
  for (const auto& [pair, list] : pairs_) out.insert(out.end(), list.begin(), list.end());
  return out;
}

void RadioTrace::write(std::ostream& out) const {
  out << kHeader << '\n';
  char buf[160];
  for (const TraceWindow& w : windows()) {
    std::snprintf(buf, sizeof buf, "%c,%c,%.9f,%.9f,%.17g,%.17g,%d\n", w.robot_a, w.robot_b, w.start, w.duration,
                  w.throughput_Bps, w.latency, w.connected ? 1 : 0);
    out << buf;
  }
}

}  // namespace cosmo::comm
