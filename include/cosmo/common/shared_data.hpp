#pragma once
// Locating ../shared (real scans, the reference JRL) for tests, benchmarks and tools. The environment
// variable COSMO_SHARED_DIR overrides the folder configured at build time (the checkout's ../shared).
#include <optional>
#include <string>

namespace cosmo {

/// The shared folder when it exists, else std::nullopt.
std::optional<std::string> sharedDir();
/// sharedDir()/relative when that path exists, else std::nullopt.
std::optional<std::string> sharedPath(const std::string& relative);

}  // namespace cosmo
