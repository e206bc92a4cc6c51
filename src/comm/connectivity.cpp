#include "cosmo/comm/connectivity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace cosmo::comm {

namespace {

double rounded(double v, double per_unit) {
  const double r = std::round(v * per_unit) / per_unit;
  return r == 0.0 ? 0.0 : r;  // no -0
}

std::string direction(char from, char to) { return std::string(1, from) + ">" + to; }

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

double Connectivity::connectedFraction(const PairConnectivity& p) const {
  const double run = runSeconds();
  return run > 0.0 ? p.connected_s / run : 0.0;
}

std::vector<std::string> Connectivity::describe() const {
  std::vector<std::string> lines;
  for (const PairConnectivity& p : pairs) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%c-%c %.1f %% connected, %llu disconnection%s, delivered / dropped %llu / %llu %s, %llu / %llu %s, "
                  "%.0f kB/s while connected",
                  p.a, p.b, 100.0 * connectedFraction(p), static_cast<unsigned long long>(p.disconnections),
                  p.disconnections == 1 ? "" : "s", static_cast<unsigned long long>(p.delivered_ab),
                  static_cast<unsigned long long>(p.dropped_ab), direction(p.a, p.b).c_str(),
                  static_cast<unsigned long long>(p.delivered_ba), static_cast<unsigned long long>(p.dropped_ba),
                  direction(p.b, p.a).c_str(), p.throughputConnectedBps() / 1000.0);
    lines.push_back(buf);
  }
  return lines;
}

nlohmann::json Connectivity::toJson() const {
  using nlohmann::json;
  json pc = json::array();
  for (double v : pairs_connected) pc.push_back(rounded(v, 1e4));
  json ps = json::array();
  for (const PairConnectivity& p : pairs) {
    json up = json::array();
    for (const auto& [s, e] : p.up) up.push_back({rounded(s, 1e3), rounded(e, 1e3)});
    json w = json::array();
    for (double v : p.window_Bps) w.push_back(rounded(v, 10.0));
    ps.push_back({{"robots", std::string{p.a, p.b}},
                  {"both_on_s", rounded(p.both_on_s, 1e3)},
                  {"connected_s", rounded(p.connected_s, 1e3)},
                  {"connected_fraction", rounded(connectedFraction(p), 1e4)},
                  {"disconnections", p.disconnections},
                  {"delivered", {{direction(p.a, p.b), p.delivered_ab}, {direction(p.b, p.a), p.delivered_ba}}},
                  {"dropped", {{direction(p.a, p.b), p.dropped_ab}, {direction(p.b, p.a), p.dropped_ba}}},
                  {"bytes", rounded(p.bytes, 1.0)},
                  {"bytes_connected", rounded(p.bytes_connected, 1.0)},
                  {"throughput_connected_Bps", rounded(p.throughputConnectedBps(), 10.0)},
                  {"up", up},
                  {"window_Bps", w}});
  }
  return {{"step_s", step_s},
          {"window_s", window_s},
          {"start_s", rounded(start_s, 1e3)},
          {"end_s", rounded(end_s, 1e3)},
          {"steps", steps},
          {"run_s", rounded(runSeconds(), 1e3)},
          {"time_origin_ns", time_origin_ns},
          {"comm", {{"d_init", d_init}, {"trace", trace}}},
          {"robots", robots},
          {"pairs_connected", pc},
          {"pairs", ps}};
}

Connectivity Connectivity::fromJson(const nlohmann::json& j, const std::string& where) {
  try {
    Connectivity c;
    c.step_s = j.at("step_s").get<double>();
    c.window_s = j.at("window_s").get<double>();
    c.start_s = j.at("start_s").get<double>();
    c.end_s = j.at("end_s").get<double>();
    c.steps = j.at("steps").get<std::uint64_t>();
    c.time_origin_ns = j.at("time_origin_ns").get<StampNs>();
    c.d_init = j.at("comm").at("d_init").get<double>();
    c.trace = j.at("comm").at("trace").get<std::string>();
    c.robots = j.at("robots").get<std::string>();
    c.pairs_connected = j.at("pairs_connected").get<std::vector<double>>();
    for (const auto& o : j.at("pairs")) {
      PairConnectivity p;
      const std::string ab = o.at("robots").get<std::string>();
      if (ab.size() != 2) throw std::runtime_error("a pair's robots are not two ids: " + ab);
      p.a = ab[0];
      p.b = ab[1];
      p.both_on_s = o.at("both_on_s").get<double>();
      p.connected_s = o.at("connected_s").get<double>();
      p.disconnections = o.at("disconnections").get<std::uint64_t>();
      p.delivered_ab = o.at("delivered").at(direction(p.a, p.b)).get<std::uint64_t>();
      p.delivered_ba = o.at("delivered").at(direction(p.b, p.a)).get<std::uint64_t>();
      p.dropped_ab = o.at("dropped").at(direction(p.a, p.b)).get<std::uint64_t>();
      p.dropped_ba = o.at("dropped").at(direction(p.b, p.a)).get<std::uint64_t>();
      p.bytes = o.at("bytes").get<double>();
      p.bytes_connected = o.at("bytes_connected").get<double>();
      for (const auto& u : o.at("up")) p.up.emplace_back(u.at(0).get<double>(), u.at(1).get<double>());
      p.window_Bps = o.at("window_Bps").get<std::vector<double>>();
      c.pairs.push_back(p);
    }
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(where + ": not a connectivity record: " + e.what());
  } catch (const std::runtime_error& e) { throw std::runtime_error(where + ": " + e.what()); }
}

Connectivity Connectivity::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) { throw std::runtime_error(path + ": not JSON: " + e.what()); }
  return fromJson(j, path);
}

ConnectivityTracker::ConnectivityTracker(std::vector<char> robots, double step, double window)
    : step_(step), window_(window) {
  if (!(step > 0.0) || !(window > 0.0)) throw std::invalid_argument("ConnectivityTracker: step and window must be > 0");
  std::sort(robots.begin(), robots.end());
  robots.erase(std::unique(robots.begin(), robots.end()), robots.end());
  robots_ = robots;
  for (std::size_t i = 0; i < robots_.size(); ++i)
    for (std::size_t j = i + 1; j < robots_.size(); ++j) {
      Pair& p = pairs_[{robots_[i], robots_[j]}];
      p.out.a = robots_[i];
      p.out.b = robots_[j];
    }
}

ConnectivityTracker::Pair& ConnectivityTracker::pair(char a, char b) {
  const auto it = pairs_.find({std::min(a, b), std::max(a, b)});
  if (it == pairs_.end())
    throw std::invalid_argument(std::string("ConnectivityTracker: no pair '") + a + "', '" + b + "'");
  return it->second;
}

void ConnectivityTracker::addBytes(char a, char b, double bytes) { pair(a, b).step_bytes += bytes; }

void ConnectivityTracker::addTransfer(const Transfer& x) {
  PairConnectivity& p = pair(x.sender, x.receiver).out;
  const bool ab = x.sender == p.a;
  const bool delivered = x.outcome == Transfer::Outcome::Delivered;
  ++(delivered ? (ab ? p.delivered_ab : p.delivered_ba) : (ab ? p.dropped_ab : p.dropped_ba));
}

std::size_t ConnectivityTracker::windowOf(double t) {
  const double mid = t - 0.5 * step_;
  const std::size_t k = mid <= start_ ? 0 : static_cast<std::size_t>(std::floor((mid - start_) / window_));
  if (window_steps_.size() <= k) {
    window_steps_.resize(k + 1, 0);
    for (auto& [ab, p] : pairs_) {
      p.window_bytes.resize(k + 1, 0.0);
      p.window_connected_steps.resize(k + 1, 0);
    }
  }
  return k;
}

void ConnectivityTracker::endStep(double t, const std::function<bool(char, char)>& connected,
                                  const std::function<bool(char)>& on) {
  if (!started_) {
    start_ = t - step_;
    started_ = true;
  }
  end_ = t;
  ++steps_;
  const std::size_t k = windowOf(t);
  ++window_steps_[k];
  for (auto& [ab, p] : pairs_) {
    const bool c = connected(ab.first, ab.second);
    if (on(ab.first) && on(ab.second)) ++p.both_on_steps;
    p.out.bytes += p.step_bytes;
    p.window_bytes[k] += p.step_bytes;
    if (c) {
      ++p.connected_steps;
      p.out.bytes_connected += p.step_bytes;
      ++p.window_connected_steps[k];
      if (p.up && !p.out.up.empty() && t - step_ - p.out.up.back().second < 0.5 * step_)
        p.out.up.back().second = t;
      else
        p.out.up.emplace_back(t - step_, t);
    } else if (p.up) {
      ++p.out.disconnections;
    }
    p.up = c;
    p.step_bytes = 0.0;
  }
}

Connectivity ConnectivityTracker::result() const {
  Connectivity c;
  c.step_s = step_;
  c.window_s = window_;
  c.start_s = start_;
  c.end_s = end_;
  c.steps = steps_;
  c.robots = std::string(robots_.begin(), robots_.end());
  c.pairs_connected.assign(window_steps_.size(), 0.0);
  for (const auto& [ab, p] : pairs_) {
    PairConnectivity out = p.out;
    out.both_on_s = static_cast<double>(p.both_on_steps) * step_;
    out.connected_s = static_cast<double>(p.connected_steps) * step_;
    out.window_Bps.resize(window_steps_.size());
    for (std::size_t k = 0; k < window_steps_.size(); ++k) {
      out.window_Bps[k] = p.window_bytes[k] / window_;
      if (window_steps_[k] > 0)
        c.pairs_connected[k] +=
            static_cast<double>(p.window_connected_steps[k]) / static_cast<double>(window_steps_[k]);
    }
    c.pairs.push_back(out);
  }
  return c;
}

std::string connectivityPath(const std::string& transfer_csv_path) {
  std::string base = transfer_csv_path;
  if (endsWith(base, ".csv")) base.resize(base.size() - 4);
  if (endsWith(base, "_transfers")) base.resize(base.size() - 10);
  return base + "_connectivity.json";
}

std::string datasetConnectivityPath(const std::string& jrl_path) {
  std::string base = jrl_path;
  if (endsWith(base, ".jrl")) base.resize(base.size() - 4);
  return connectivityPath(base + "_transfers.csv");
}

}  // namespace cosmo::comm
