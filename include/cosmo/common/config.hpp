#pragma once
// Reading parameters from YAML config files (config/*.yaml). A missing key keeps the default; a key of the
// wrong type throws std::runtime_error naming the file and the key, e.g. "config/loam.yaml:
// odometry.max_icf_iterations: expected int"; so does a key no reader knows (a typo would otherwise be ignored: see
// common/param_list.hpp).
#include <yaml-cpp/yaml.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace cosmo {

/// A YAML node plus the place it came from, for error messages.
struct ConfigNode {
  YAML::Node node;
  std::string where;  ///< "file.yaml: section.sub"
  std::string file{};  ///< the file it was loaded from (empty: made in memory)

  /// Load a file; throws naming the file when it is missing or malformed.
  static ConfigNode load(const std::string& path);
  /// Child section (an absent section is an empty node: every read keeps its default).
  ConfigNode operator[](const std::string& key) const;
  bool has(const std::string& key) const { return node && node.IsMap() && node[key]; }

  /// Throws, naming the file, the section and the key (and the nearest known key), when this section holds a key
  /// that is not in `known`.
  void rejectUnknownKeys(const std::vector<std::string>& known) const;

  /// This section as a map of single values kept as written (an absent section: empty); throws naming the section,
  /// or the key, when it is not a map or a value is not a single one. `what`: what the keys are, for the message.
  std::map<std::string, std::string> scalarMap(const std::string& what) const;

  /// Overwrite `value` with the key's value when present.
  template <typename T>
  void read(const std::string& key, T& value) const {
    if (!has(key)) return;
    try {
      value = node[key].as<T>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error(where + (where.empty() || where.back() == ' ' ? "" : ".") + key +
                               ": cannot read value '" + YAML::Dump(node[key]) + "' as the expected type");
    }
  }
};

}  // namespace cosmo
