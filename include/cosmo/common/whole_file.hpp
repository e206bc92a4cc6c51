#pragma once
// A whole file read into a string (bytes as they are).
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cosmo {

/// The file's bytes; nullopt when it cannot be opened.
inline std::optional<std::string> readWholeFileIfAny(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The file's bytes; "" when it cannot be opened (or is empty).
inline std::string readWholeFileOrEmpty(const std::string& path) { return readWholeFileIfAny(path).value_or(""); }

/// The file's bytes; std::runtime_error "<path>: cannot read" when it cannot be opened.
inline std::string readWholeFile(const std::string& path) {
  std::optional<std::string> bytes = readWholeFileIfAny(path);
  if (!bytes) throw std::runtime_error(path + ": cannot read");
  return std::move(*bytes);
}

}  // namespace cosmo
