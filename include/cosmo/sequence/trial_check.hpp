#pragma once
// The pre-flight check of a sequence (cosmo_check, the start of cosmo_generate and of the player): from the first
// scans of each trial and its reference, one line per trial, and the reasons the run could not produce a labelled
// dataset. ROS-free: a container reader fills a TrialProbe (what it found in the bag), this judges it.
#include <string>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/sequence_config.hpp"

namespace cosmo::sequence {

/// What a trial's `bag:` turned out to be.
enum class BagState {
  Missing,     ///< no such file or folder
  Unreadable,  ///< there, but it cannot be read (not a regular file, permissions)
  NotABag,     ///< readable, but neither a ROS 1 bag nor a ROS 2 sqlite3 bag (an empty file among them)
  Damaged,     ///< a bag whose header, records or index cannot be read
  Empty,       ///< a valid bag that records nothing (no connections or topics)
  Ok,
};

/// What a reader found at the start of a trial's bag.
struct TrialProbe {
  BagState bag = BagState::Missing;
  std::string error;  ///< why the bag or the topic could not be read ("" when it could)
  bool topic_found = false;
  std::vector<std::string> topics;  ///< "name (type)" of every topic of the bag (shown when `topic` is missing)
  /// The cloud's point fields and which hold time and ring: "x:float32@0 ... (time t (ns ...), ring ring)".
  std::string fields;
  std::size_t messages = 0;                 ///< messages on the topic (0: an empty topic, no error)
  StampNs first_stamp = 0, last_stamp = 0;  ///< sweep-end stamps of the first and the last message
  std::vector<Scan> first_scans;       ///< the first few scans, decoded with the trial's convention, at the sweep end
  std::size_t points_in_messages = 0;  ///< width * height of those messages (invalid returns included)
};

struct TrialCheck {
  char robot = 'a';
  std::string line;                 ///< one line for the console
  std::vector<std::string> errors;  ///< the run could not produce a labelled dataset because of these
};

/// Judges one trial. `reference`: its body reference as read (recorded time; empty with `reference_error` when it
/// could not be read or with no `reference:`); `noise_models`: the file the run will use ("" = built-in defaults).
TrialCheck checkTrial(const TrialConfig& trial, const TrialProbe& probe, const Trajectory& reference,
                      const std::string& reference_error, const std::string& noise_models);

/// Every line, then "ok: ..." or "cannot produce a labelled dataset: <reason>; ..." (returns whether ok).
bool formatChecks(const std::vector<TrialCheck>& checks, std::string& text);

}  // namespace cosmo::sequence
