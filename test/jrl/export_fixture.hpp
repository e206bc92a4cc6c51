#pragma once
// What the export tests share: the tiny example of jrl.md §12, a fresh folder per test, and a line's fields.
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace jrl_test {

namespace fs = std::filesystem;

inline const std::string kTiny = std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl";

/// A fresh, empty <temp>/cosmo_test_<name>_<pid>.
inline fs::path tempDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("cosmo_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

/// The fields of `line` between the `sep`s (none after a trailing one).
inline std::vector<std::string> splitBy(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, sep)) out.push_back(f);
  return out;
}

}  // namespace jrl_test
