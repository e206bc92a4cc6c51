#include "cosmo/common/config.hpp"
#include "cosmo/common/nearest_name.hpp"

#include <algorithm>
#include <cstddef>

namespace cosmo {

ConfigNode ConfigNode::load(const std::string& path) {
  try {
    return ConfigNode{YAML::LoadFile(path), path + ": ", path};
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(path + ": cannot open config file");
  } catch (const YAML::Exception& e) { throw std::runtime_error(path + ": malformed YAML: " + e.what()); }
}

ConfigNode ConfigNode::operator[](const std::string& key) const {
  ConfigNode child;
  if (has(key)) child.node = node[key];
  const bool root = !where.empty() && where.back() == ' ';
  child.where = where + (root || where.empty() ? "" : ".") + key;
  child.file = file;
  return child;
}

namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearestName(const std::string& key, const std::vector<std::string>& known) {
  const std::size_t limit = std::max<std::size_t>(2, key.size() / 3);
  std::string best;
  std::size_t best_distance = std::min(key.size(), limit + 1);  // a farther name is never the answer
  for (const std::string& k : known) {
    // The edit distance is at least the difference in length: such a name cannot be nearer than the best so far.
    const std::size_t length_gap = k.size() > key.size() ? k.size() - key.size() : key.size() - k.size();
    if (length_gap >= best_distance) continue;
    const std::size_t d = editDistance(key, k);
    if (d < best_distance) best = k, best_distance = d;
  }
  return best_distance <= limit ? best : std::string();
}

void ConfigNode::rejectUnknownKeys(const std::vector<std::string>& known) const {
  if (!node || !node.IsMap()) return;
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const std::string nearest = nearestName(key, known);
    const bool root = where.empty() || where.back() == ' ';
    throw std::runtime_error(where + (root ? "" : ".") + key + ": unknown parameter" +
                             (nearest.empty() ? std::string() : " (did you mean '" + nearest + "'?)"));
  }
}

std::map<std::string, std::string> ConfigNode::scalarMap(const std::string& what) const {
  std::map<std::string, std::string> values;
  if (!node) return values;
  if (!node.IsMap()) throw std::runtime_error(where + ": expected a map of " + what);
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (!kv.second.IsScalar()) throw std::runtime_error(where + "." + key + ": expected a single value (" + what + ")");
    values[key] = kv.second.as<std::string>();
  }
  return values;
}

}  // namespace cosmo
