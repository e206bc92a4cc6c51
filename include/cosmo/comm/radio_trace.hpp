#pragma once
// A radio trace: measured (or recorded) link behaviour per robot pair and time window, replayed instead of the
// distance model (comm model `trace`, docs/design.md "Radio traces"). CSV, one row per window:
//
//   # comments and blank lines are skipped
//   robot_a,robot_b,start,duration,throughput_Bps,latency,connected
//   a,b,0.0,1.0,1250000,0.012,1
//
// robot_a, robot_b: two robot ids of the team (one character each; the row holds for both directions).
// start, duration (s): the window [start, start + duration), in seconds since the run's radio time 0 (the sequence
// start rounded down to the step grid; comm_simulate: the earliest trajectory start, likewise).
// throughput_Bps: bytes per second the link carries when it is the only communication (shared by interference as
// the model shares B). latency (s): a delivered scan reaches its receiver this long after its last byte was sent.
// connected: 1 or 0, the connectivity sample C of every step in the window.
// A step at radio time t (covering (t - delta, t]) uses the window of its pair that contains t - delta / 2.
// Rejected, with the file and line: a wrong header or column count, a robot id that is not one character, a row
// pairing a robot with itself, a number that does not parse or is not finite, duration <= 0, throughput < 0,
// latency < 0, connected not 0 or 1, two windows of one pair that overlap; and (checkTeam) a robot not in the team.
#include <cstddef>
#include <istream>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace cosmo::comm {

struct TraceWindow {
  char robot_a = 0, robot_b = 0;  ///< robot_a < robot_b
  double start = 0.0, duration = 0.0;
  double throughput_Bps = 0.0;
  double latency = 0.0;
  bool connected = false;
  std::size_t line = 0;  ///< line in the file (0: made in memory)

  double end() const { return start + duration; }
};

/// One connectivity sample the radio drew for a pair at a step (RadioSimulator::recordLinks).
struct LinkRecord {
  char robot_a = 0, robot_b = 0;  ///< robot_a < robot_b
  double step_time = 0.0;         ///< radio time of the step
  bool connected = false;
  double throughput_Bps = 0.0;
  double latency = 0.0;
};

class RadioTrace {
 public:
  /// Reads a trace file; throws std::runtime_error "<file>:<line>: <problem>".
  static RadioTrace read(const std::string& path);
  /// Parses a trace; `source` names it in errors.
  static RadioTrace parse(std::istream& in, const std::string& source);
  /// The windows of recorded samples: each sample the window (t - step, t], consecutive samples of a pair with
  /// the same values merged. Times relative to `origin` (radio time of trace time 0).
  static RadioTrace fromRecords(const std::vector<LinkRecord>& records, double step, double origin = 0.0);

  /// Throws std::runtime_error "<file>:<line>: robot 'x' is not in the team (a, b, c)" for a window naming a robot
  /// outside `team`.
  void checkTeam(const std::vector<char>& team) const;
  /// The window of the pair {a, b} that contains trace time t, nullptr when none.
  const TraceWindow* find(char a, char b, double t) const;
  /// Writes the CSV (header and one row per window, pairs in order, then start).
  void write(std::ostream& out) const;

  const std::string& source() const { return source_; }
  std::size_t windowCount() const;
  /// Every window, pairs in order, then start.
  std::vector<TraceWindow> windows() const;

 private:
  void add(TraceWindow w);  ///< throws on an overlap with a window of the same pair

  std::string source_;
  std::map<std::pair<char, char>, std::vector<TraceWindow>> pairs_;  ///< sorted by start
};

}  // namespace cosmo::comm
