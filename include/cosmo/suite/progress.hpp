#pragma once
// The suite's progress line: datasets done / running / left, the sequence time still to process, and an ETA from
// the rate at which this run has processed sequence time so far (finished jobs and the progress lines of the
// running ones' logs). Until the run has processed kEtaAfterShare of its sequence time the ETA is left out: a rate
// taken from the first seconds (a first pass decompressing, an estimate that prints no progress) is far off.
#include <string>

namespace cosmo::suite {

constexpr double kEtaAfterShare = 0.02;

/// How far cosmo_generate's log says it is: the sequence seconds its progress lines reached, summed over its comm
/// models' passes (the last line of each "[<comm>] t / T s" kind), and the sequence's length T (0 when not printed).
struct LogProgress {
  double done_s = 0.0;
  double length_s = 0.0;
};
LogProgress readLogProgress(const std::string& log_text);

struct ProgressCounts {
  std::size_t done = 0, skipped = 0, failed = 0, running = 0, left = 0;  ///< datasets
  double remaining_s = 0.0;  ///< sequence seconds still to process (all comm-model passes)
  double processed_s = 0.0;  ///< sequence seconds processed by this run so far
  double elapsed_s = 0.0;    ///< wall time of this run so far
};

/// "[suite] 3 done, 1 skipped as current, 0 failed, 2 running, 4 left; 512 s of sequence to process, ETA 6 min 10 s".
std::string progressLine(const ProgressCounts& c);

/// "1 h 02 min", "6 min 10 s", "42 s".
std::string formatDuration(double seconds);

}  // namespace cosmo::suite
