#pragma once
// The sequence the player replays, resolved and checked before anything is played: its config (the built-in
// synthetic sequence when none is given), effective seed, time synchronization, references and the end of the
// replay. Resolving announces the robots first (/player/robots: the launch starts their front-ends meanwhile)
// and the resolved sequence's origin at the end (resolved_sequence.hpp).
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

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

/// Loads, announces and checks the sequence (throws std::runtime_error when the pre-flight check fails: a run that
/// cannot be labelled does not start).
PlayedSequence resolvePlayedSequence(const SequenceChoice& choice);

}  // namespace cosmo::ros_glue
