#pragma once
// For readers that take a path: the input written to a file of a private temporary folder (made once per process
// and removed at its exit) under $COSMO_FUZZ_SCRATCH, else /dev/shm (in memory) when there is one, else the
// temporary folder; rewritten for every input.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace cosmo::fuzz {

inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    const char* env = std::getenv("COSMO_FUZZ_SCRATCH");
    const bool shm = ::access("/dev/shm", W_OK) == 0;
    const std::filesystem::path base = env && *env ? std::filesystem::path(env)
                                       : shm       ? std::filesystem::path("/dev/shm")
                                                   : std::filesystem::temp_directory_path();
    std::string pattern = (base / "cosmo_fuzz_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::logic_error("cannot make a temporary folder");
    static const std::string keep = pattern;
    std::atexit([] { std::error_code ec; std::filesystem::remove_all(keep, ec); });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

/// Writes `size` bytes to `<scratch>/<name>` and returns its path.
inline std::string inputFile(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = (scratchDir() / name).string();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0)
    throw std::logic_error("cannot write " + path);
  return path;
}

}  // namespace cosmo::fuzz
