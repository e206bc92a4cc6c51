#pragma once
// Where the sequence the player replays came from, on the parameter server for users and tools (the rostest runs
// cosmo_generate on the same file and seed): the config path (the built-in sequence is generated first), its
// effective seed and the data root, and its own registration keys. The lockstep nodes read no file: they take the
// resolved sequence from the player's latched topics (team_sequence_msg.hpp) and its registration keys from here.
#include <map>
#include <optional>
#include <string>

#include <ros/node_handle.h>

#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/trials/sequence_resolution.hpp"

namespace cosmo::ros_glue {

/// Parameter names: the config path and its (effective) seed, a decimal string (64 bits).
inline constexpr const char* kResolvedSequenceParam = "/player/resolved_sequence";
inline constexpr const char* kResolvedSeedParam = "/player/resolved_seed";
/// The data root the player resolved the trials' paths against (the config's own precedence applies when empty).
inline constexpr const char* kResolvedDataRootParam = "/player/resolved_data_root";

/// The sequence's own `registration:` keys (a map of config/registration.yaml keys to their values as written;
/// absent when it has none): the front-ends apply them over their ~config_dir's registration.yaml.
inline constexpr const char* kResolvedRegistrationParam = "/player/resolved_registration";

/// Where the player's sequence is: its config path and the data root it resolved the trials against.
struct ResolvedSequence {
  std::string path, data_root;
  std::map<std::string, std::string> registration;  ///< its own registration keys (kResolvedRegistrationParam)
  /// Reads the config file (throws naming it when it cannot): for what only the file holds (noise-model file,
  /// metadata lines); the keys above need no file.
  sequence::SequenceConfig load() const { return sequence::SequenceConfig::load(path, data_root); }
};

/// The sequence the player resolved, from the parameters; none while no player has resolved one (live robots).
std::optional<ResolvedSequence> resolvedSequence();

/// Sets the parameters (the player); the path last, once the others are set.
void publishResolvedSequence(const std::string& path, unsigned long long seed, const std::string& data_root = "",
                             const std::map<std::string, std::string>& registration = {});

/// ~sequence, ~data_root, ~seed (-1: the config's), ~max_seconds, ~simulate_config, ~simulate_out, ~noise_models,
/// ~config_dir: the sequence a node plays (player, trial_player) or records (recorder), as its parameters name it.
trials::SequenceChoice readSequenceChoice(const ros::NodeHandle& pnh);

}  // namespace cosmo::ros_glue
