#pragma once
// Where the sequence the player replays came from, on the parameter server for users and tools (the rostest runs
// cosmo_generate on the same file and seed): the config path (the built-in sequence is generated first), its
// effective seed and the data root. The lockstep nodes do not read these: they take the resolved sequence from the
// player's latched topics (team_sequence_msg.hpp).
#include <string>

namespace cosmo::ros_glue {

/// Parameter names: the config path and its (effective) seed, a decimal string (64 bits).
inline constexpr const char* kResolvedSequenceParam = "/player/resolved_sequence";
inline constexpr const char* kResolvedSeedParam = "/player/resolved_seed";
/// The data root the player resolved the trials' paths against (the config's own precedence applies when empty).
inline constexpr const char* kResolvedDataRootParam = "/player/resolved_data_root";

/// Sets the parameters (the player).
void publishResolvedSequence(const std::string& path, unsigned long long seed, const std::string& data_root = "");

}  // namespace cosmo::ros_glue
