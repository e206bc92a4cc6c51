#include "cosmo/common/shared_data.hpp"

#include <cstdlib>
#include <filesystem>

#ifndef COSMO_DEFAULT_SHARED_DIR
#define COSMO_DEFAULT_SHARED_DIR "../shared"
#endif

namespace cosmo {

std::optional<std::string> sharedDir() {
  const char* env = std::getenv("COSMO_SHARED_DIR");
  const std::string dir = (env && *env) ? env : COSMO_DEFAULT_SHARED_DIR;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) return std::filesystem::weakly_canonical(dir, ec).string();
  return std::nullopt;
}

std::optional<std::string> sharedPath(const std::string& relative) {
  const auto dir = sharedDir();
  if (!dir) return std::nullopt;
  const auto p = std::filesystem::path(*dir) / relative;
  std::error_code ec;
  if (std::filesystem::exists(p, ec)) return p.string();
  return std::nullopt;
}

}  // namespace cosmo
