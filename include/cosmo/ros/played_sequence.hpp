#pragma once
// The sequence the player replays, resolved and checked before anything is played: its config (the built-in
// synthetic sequence when none is given), effective seed, time synchronization, references and the end of the
// replay. Resolving announces the robots first (/player/robots: the launch starts their front-ends meanwhile)
// and the resolved sequence's origin at the end (resolved_sequence.hpp). The trials are read here, or, with
// robot-side playback, each on its robot's machine (robot_playback.hpp): the same timing and references either way.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"
#include "cosmo/pipeline/trial_basis.hpp"

namespace cosmo::ros_glue {

/// Where the sequence comes from (the player's parameters).
struct SequenceChoice {
  std::string sequence;         ///< config path; empty: the built-in sequence
  std::string data_root;        ///< empty: the config's precedence
  std::string simulate_config;  ///< the built-in sequence's simulation config (empty: the default)
  std::string simulate_out = "/tmp/cosmo_builtin_sequence";
  std::string noise_models, config_dir;
  int seed = -1;             ///< -1: the config's
  double max_seconds = 0.0;  ///< 0: all
};

struct PlayedSequence {
  pipeline::SequenceConfig config;
  pipeline::SequenceTiming timing;
  std::map<char, Trajectory> references;
  StampNs end = 0;
  std::vector<char> robots() const;
  double seconds() const { return toSeconds(end - timing.start()); }
};

/// The config `choice` names (the built-in sequence is generated first, once: cached), with its seed override.
pipeline::SequenceConfig loadSequenceChoice(const SequenceChoice& choice);

/// What the timing and references take from each trial, however the trials are read.
using TrialBases = std::function<std::map<char, pipeline::TrialBasis>(const pipeline::SequenceConfig&)>;

/// The player reads every trial: the pre-flight check (throws std::runtime_error when it fails: a run that cannot
/// be labelled does not start), then each trial's basis from its bag and reference.
std::map<char, pipeline::TrialBasis> readTrialBases(const pipeline::SequenceConfig& config);

/// Loads and announces the sequence, takes its trials' bases from `trial_bases` (readTrialBases, or the robots'
/// announcements when each robot plays its own trial) and resolves the timing and references from them.
PlayedSequence resolvePlayedSequence(const SequenceChoice& choice, const TrialBases& trial_bases = readTrialBases);

}  // namespace cosmo::ros_glue
