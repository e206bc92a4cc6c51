#pragma once
// Connectivity over a radio run, per robot pair (docs/design.md "Connectivity"): the time the pair was connected
// (LinkModel::connected, one step of delta at a time), its disconnections (a connected step followed by one that is
// not), the scans delivered and dropped (timed out) in each direction, the bytes that got through and the
// throughput while connected, and a time series: the intervals the link was up and the throughput per window.
// The RadioSimulator feeds one ConnectivityTracker from its steps; the transfer log writes its result beside the
// CSV as `<dataset>_connectivity.json` (comm/transfer_log.hpp). Times are radio time (s since time_origin_ns).
//
// JSON (one object; numbers rounded: times to 1 ms, bytes to 1 B, rates to 0.1 B/s, fractions to 1e-4):
//   step_s, window_s, start_s (the first step's start), end_s (the last step's end), steps, run_s (steps x step),
//   time_origin_ns, comm {d_init, trace}, robots "abc",
//   pairs_connected [per window: mean number of connected pairs over its steps],
//   pairs [{robots "ab", both_on_s, connected_s, connected_fraction (of run_s), disconnections,
//           delivered {"a>b", "b>a"}, dropped {"a>b", "b>a"}, bytes, bytes_connected,
//           throughput_connected_Bps (bytes_connected / connected_s; 0 when never connected),
//           up [[start, end], ...], window_Bps [per window: bytes through / window_s]}]
// Window k covers [start_s + k window_s, start_s + (k + 1) window_s); a step belongs to the window holding its
// middle.
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cosmo/comm/transfer.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::comm {

struct PairConnectivity {
  char a = 0, b = 0;  ///< a < b
  double both_on_s = 0.0, connected_s = 0.0;
  std::uint64_t disconnections = 0;
  std::uint64_t delivered_ab = 0, delivered_ba = 0, dropped_ab = 0, dropped_ba = 0;
  double bytes = 0.0;                         ///< every byte that got through between them, connected or not
  double bytes_connected = 0.0;               ///< in the steps they were connected
  std::vector<std::pair<double, double>> up;  ///< [start, end] of each interval the link was up
  std::vector<double> window_Bps;             ///< throughput per window

  /// bytes_connected / connected_s; 0 when never connected.
  double throughputConnectedBps() const { return connected_s > 0.0 ? bytes_connected / connected_s : 0.0; }
};

struct Connectivity {
  double step_s = 0.0, window_s = 1.0, start_s = 0.0, end_s = 0.0;
  std::uint64_t steps = 0;
  StampNs time_origin_ns = 0;
  double d_init = 0.0;
  std::string trace;  ///< the radio trace's file ("": none)
  std::string robots;
  std::vector<double> pairs_connected;  ///< per window
  std::vector<PairConnectivity> pairs;  ///< in robot order

  double runSeconds() const { return static_cast<double>(steps) * step_s; }
  /// connected_s / runSeconds() of a pair; 0 for an empty run.
  double connectedFraction(const PairConnectivity& p) const;

  /// One line per pair: "a-b 31.2 % connected, 1 disconnection, delivered / dropped 12 / 0 a>b, 9 / 1 b>a,
  /// 812 kB/s while connected".
  std::vector<std::string> describe() const;
  /// The JSON above (rounded).
  nlohmann::json toJson() const;
  /// Throws std::runtime_error naming `where` when `j` is not such an object.
  static Connectivity fromJson(const nlohmann::json& j, const std::string& where);
  /// Reads a `_connectivity.json` file; throws std::runtime_error naming it.
  static Connectivity read(const std::string& path);
};

class ConnectivityTracker {
 public:
  /// `robots` sorted and de-duplicated internally; `step` the radio's delta, `window` the time series' window (s).
  ConnectivityTracker(std::vector<char> robots, double step, double window = 1.0);

  /// Bytes that got through between a and b (either direction) in the current step.
  void addBytes(char a, char b, double bytes);
  /// A transfer that ended in the current step (delivered: when it reached the receiver).
  void addTransfer(const Transfer& x);
  /// Closes the step ending at radio time t: `connected(a, b)` (a < b) for each pair, `on(r)` for each robot.
  void endStep(double t, const std::function<bool(char, char)>& connected, const std::function<bool(char)>& on);

  /// The figures so far (the run's origin and comm fields left to the caller).
  Connectivity result() const;

 private:
  struct Pair {
    PairConnectivity out;  ///< its seconds filled in by result() from the step counts
    std::uint64_t both_on_steps = 0, connected_steps = 0;
    bool up = false;
    double step_bytes = 0.0;
    std::vector<double> window_bytes;
    std::vector<std::uint64_t> window_connected_steps;
  };
  Pair& pair(char a, char b);
  std::size_t windowOf(double t);

  std::vector<char> robots_;
  double step_, window_;
  bool started_ = false;
  double start_ = 0.0, end_ = 0.0;
  std::uint64_t steps_ = 0;
  std::vector<std::uint64_t> window_steps_;
  std::map<std::pair<char, char>, Pair> pairs_;
};

/// `<csv_path without .csv and a trailing _transfers>_connectivity.json`: where the transfer log's connectivity goes.
std::string connectivityPath(const std::string& transfer_csv_path);
/// The connectivity of the dataset `<dataset>.jrl`: `<dataset>_connectivity.json` beside it (its transfer log is
/// `<dataset>_transfers.csv`).
std::string datasetConnectivityPath(const std::string& jrl_path);

}  // namespace cosmo::comm
