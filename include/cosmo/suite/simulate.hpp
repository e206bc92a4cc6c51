#pragma once
// A suite's `simulate:` entries: the sequence config that cosmo_simulate writes (and caches in its own cache, so a
// second suite run costs nothing), its output in a log.
#include <functional>
#include <string>

#include "cosmo/suite/suite_file.hpp"

namespace cosmo::suite {

/// A resolver for PlanOptions::simulate: runs `<program_dir>/cosmo_simulate --config SIM --layout L`, its output
/// into `<log_dir>/simulate-<sim name>-<layout>.log`, and returns the path it prints last. Throws naming the entry
/// and the log when it fails.
std::function<std::string(const SequenceEntry&)> simulateWith(const std::string& program_dir,
                                                              const std::string& log_dir);

}  // namespace cosmo::suite
