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

/// What a reader found at the start of a trial's bag.
struct TrialProbe {
  bool bag_found = false;
  std::string error;  ///< why the bag or the topic could not be read ("" when it could)
  bool topic_found = false;
  std::vector<std::string> topics;          ///< "name (type)" of every topic of the bag (shown when `topic` is missing)
  std::string fields;                       ///< the cloud's point fields, e.g. "x:float32 y:float32 z:float32 t:uint32"
  std::size_t messages = 0;                 ///< messages on the topic
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
