#pragma once
// The built-in synthetic sequence, which the launch plays when it is given no sequence config: the sequence YAML
// that `cosmo_simulate --config CONFIG --out OUT` writes (cosmo_simulate caches it by its parameters, so only the
// first run generates the world).
#include <string>

namespace cosmo::sequence {

struct BuiltInSequence {
  std::string simulate_config;  ///< the simulation's config (default: config/sim/default.yaml)
  std::string command;          ///< the cosmo_simulate command line that writes it
  std::string path;             ///< the sequence YAML it writes
};

/// `simulate_config` empty: config/sim/default.yaml; `tools_dir`: where cosmo_simulate is (programDir()).
/// Throws std::runtime_error when the simulation's config cannot be read.
BuiltInSequence builtInSequence(const std::string& simulate_config, const std::string& out,
                                const std::string& tools_dir);
/// Runs the command; returns the sequence YAML. Throws std::runtime_error naming the command when it fails.
std::string writeBuiltInSequence(const BuiltInSequence& sequence);
/// The folder of the running program (the tools are installed beside each other); "." when unknown.
std::string programDir();

}  // namespace cosmo::sequence
