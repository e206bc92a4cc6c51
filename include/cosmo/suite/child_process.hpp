#pragma once
// Running a program as a child process: its output into a log file, killed with its parent (so that a suite
// killed with SIGKILL leaves no job running behind it), and its cost (wall time, CPU of it and everything it
// waited for, peak memory) measured by the kernel (wait4).
#include <sys/types.h>

#include <string>
#include <vector>

namespace cosmo::suite {

struct ChildResult {
  int exit_code = -1;  ///< -1 when a signal ended it
  int signal = 0;
  double wall_s = 0.0, cpu_s = 0.0, peak_rss_mb = 0.0;
  /// "exit code N" / "killed by signal N (NAME)".
  std::string describe() const;
};

/// Starts argv[0] (a path) with argv; stdout and stderr go to `log_path` (appended; "" = inherited). The child
/// gets SIGKILL when this process ends. Throws std::runtime_error when it cannot be started.
pid_t spawnChild(const std::vector<std::string>& argv, const std::string& log_path);

/// Waits for `pid` (blocking, or 0 / false at once when `block` is false and it still runs).
bool waitChild(pid_t pid, bool block, ChildResult& result, double started_wall_s);

/// Runs argv to its end: spawnChild + waitChild.
ChildResult runChild(const std::vector<std::string>& argv, const std::string& log_path);

/// Seconds on a monotonic clock.
double monotonicSeconds();

/// The last `lines` lines of a text file ("" when it cannot be read).
std::string tailOfFile(const std::string& path, int lines);

}  // namespace cosmo::suite
