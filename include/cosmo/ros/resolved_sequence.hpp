#pragma once
// The sequence the player replays, handed to the lockstep nodes (frontend, comm_broker) so that they use the
// offline driver's own inputs: the reference trajectories as read from the CSVs (not rebuilt from rounded
// reference_pose messages), the time synchronization and the seed. The player resolves the config path (the
// built-in sequence is generated first) and its seed, and sets them on the parameter server before it
// publishes anything; the nodes read them when their first lockstep input arrives.
#include <string>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

namespace cosmo::ros_glue {

/// Parameter names: the config path and its (effective) seed, a decimal string (64 bits).
inline constexpr const char* kResolvedSequenceParam = "/player/resolved_sequence";
inline constexpr const char* kResolvedSeedParam = "/player/resolved_seed";
/// The data root the player resolved the trials' paths against (the config's own precedence applies when empty).
inline constexpr const char* kResolvedDataRootParam = "/player/resolved_data_root";

struct ResolvedSequence {
  pipeline::SequenceConfig config;  ///< seed = the effective seed
  pipeline::SequenceTiming timing;
  /// The sensor reference trajectory of `robot` in sequence time (empty: none, or an unknown robot).
  Trajectory reference(char robot) const;
};

/// Loads the config at `path` (trials below `data_root`, empty: the config's precedence), sets its seed,
/// synchronizes it (reads the bags' spans). Throws on bad input.
ResolvedSequence resolveSequence(const std::string& path, unsigned long long seed, const std::string& data_root = "");
/// Sets the parameters (the player).
void publishResolvedSequence(const std::string& path, unsigned long long seed, const std::string& data_root = "");
/// Reads the two parameters, waiting up to `timeout_s` (wall) for them, and resolves the sequence. Throws
/// std::runtime_error when they do not appear.
ResolvedSequence readResolvedSequence(double timeout_s);

}  // namespace cosmo::ros_glue
