#include "cosmo/suite/suite_file.hpp"

#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

std::string relativeTo(const fs::path& dir, const std::string& path) {
  if (path.empty()) return path;
  return fs::weakly_canonical(fs::path(path).is_absolute() ? fs::path(path) : dir / path).string();
}

std::string scalar(const ConfigNode& node, const std::string& key) {
  if (!node.has(key)) return "";
  if (!node.node[key].IsScalar()) throw std::runtime_error(node[key].where + ": expected a single value");
  return node.node[key].as<std::string>();
}

std::vector<std::string> scalarList(const ConfigNode& node, const std::string& key) {
  std::vector<std::string> out;
  if (!node.has(key)) return out;
  const YAML::Node n = node.node[key];
  if (n.IsScalar()) return {n.as<std::string>()};
  if (!n.IsSequence()) throw std::runtime_error(node[key].where + ": expected a list of names");
  for (const auto& item : n) {
    if (!item.IsScalar()) throw std::runtime_error(node[key].where + ": expected a list of names");
    out.push_back(item.as<std::string>());
  }
  return out;
}

/// The entries of a list section, each with its place ("file: sequences[2]").
std::vector<ConfigNode> listItems(const ConfigNode& root, const std::string& key) {
  std::vector<ConfigNode> items;
  if (!root.has(key)) return items;
  if (!root.node[key].IsSequence()) throw std::runtime_error(root[key].where + ": expected a list");
  int i = 0;
  for (const auto& item : root.node[key]) {
    ConfigNode c{item, root[key].where + "[" + std::to_string(i++) + "]"};
    if (!item.IsMap()) throw std::runtime_error(c.where + ": expected a map");
    items.push_back(c);
  }
  return items;
}

SequenceEntry readSequence(const ConfigNode& item, const fs::path& dir) {
  item.rejectUnknownKeys({"sequence", "simulate", "layout", "label", "data_root"});
  SequenceEntry e;
  e.where = item.where;
  e.label = scalar(item, "label");
  e.sequence = relativeTo(dir, scalar(item, "sequence"));
  e.simulate = relativeTo(dir, scalar(item, "simulate"));
  e.data_root = scalar(item, "data_root");
  if (item.has("layout")) e.layout = scalar(item, "layout");
  if (e.sequence.empty() == e.simulate.empty())
    throw std::runtime_error(item.where + ": give one of `sequence: FILE` or `simulate: SIM_CONFIG`");
  if (e.layout != "cosmo" && e.layout != "mcd" && e.layout != "cu-multi")
    throw std::runtime_error(item["layout"].where + ": expected cosmo, mcd or cu-multi, got '" + e.layout + "'");
  if (!e.simulate.empty() && !e.data_root.empty())
    throw std::runtime_error(item["data_root"].where + ": a simulated sequence lies beside its config");
  if (!e.label.empty() && nameSafe(e.label) != e.label)
    throw std::runtime_error(item["label"].where + ": use letters, digits, '.', '-' and '_' only");
  return e;
}

EstimateEntry readEstimate(const ConfigNode& item) {
  item.rejectUnknownKeys({"estimate", "from", "trial", "for", "why"});
  EstimateEntry e;
  e.where = item.where;
  e.name = scalar(item, "estimate");
  e.from = scalar(item, "from");
  e.trial = scalar(item, "trial");
  e.used_by = scalarList(item, "for");
  e.why = scalar(item, "why");
  if (e.name.empty() || e.from.empty() || e.trial.empty())
    throw std::runtime_error(item.where + ": an estimate needs `estimate: NAME`, `from: LABEL` and `trial: ID`");
  if (nameSafe(e.name) != e.name)
    throw std::runtime_error(item["estimate"].where + ": use letters, digits, '.', '-' and '_' only");
  return e;
}

VariantValue readValue(const YAML::Node& n, const std::string& where) {
  VariantValue v;
  v.where = where;
  if (n.IsScalar()) {
    v.scalar = n.as<std::string>();
  } else if (n.IsMap()) {
    for (const auto& kv : n) {
      if (!kv.second.IsScalar()) throw std::runtime_error(where + "." + kv.first.as<std::string>() + ": expected a single value");
      v.fields[kv.first.as<std::string>()] = kv.second.as<std::string>();
    }
  } else {
    throw std::runtime_error(where + ": expected a value or a map of values");
  }
  return v;
}

std::vector<VariantAxis> readVariants(const ConfigNode& root) {
  std::vector<VariantAxis> axes;
  if (!root.has("variants")) return axes;
  const ConfigNode section = root["variants"];
  if (!section.node.IsMap()) throw std::runtime_error(section.where + ": expected a map of variant keys");
  section.rejectUnknownKeys(variantKeyNames());
  for (const auto& kv : section.node) {
    VariantAxis axis;
    axis.key = kv.first.as<std::string>();
    const std::string where = section[axis.key].where;
    std::string sub;
    const VariantKey* key = findVariantKey(axis.key, sub);
    const bool list = kv.second.IsSequence();
    for (std::size_t i = 0; i < (list ? kv.second.size() : 1); ++i) {
      const std::string at = list ? where + "[" + std::to_string(i) + "]" : where;
      axis.values.push_back(readValue(list ? kv.second[i] : kv.second, at));
      key->check(sub, axis.values.back());
    }
    if (axis.values.empty()) throw std::runtime_error(where + ": no values");
    if (axis.key == "repeats" && list) throw std::runtime_error(where + ": expected one number of repeats");
    axes.push_back(axis);
  }
  return axes;
}

}  // namespace

SuiteFile SuiteFile::load(const std::string& path) {
  SuiteFile s;
  s.path = fs::absolute(path).string();
  const ConfigNode root = ConfigNode::load(s.path);
  if (!root.node.IsMap()) throw std::runtime_error(s.path + ": expected a map (name, comm, sequences, ...)");
  root.rejectUnknownKeys({"name", "comm", "max_seconds", "config_dir", "sequences", "noise_models", "variants"});
  const fs::path dir = fs::path(s.path).parent_path();
  s.name = scalar(root, "name");
  if (s.name.empty()) s.name = fs::path(s.path).stem().string();
  if (root.has("comm")) s.comms = scalarList(root, "comm");
  root.read("max_seconds", s.max_seconds);
  if (s.max_seconds < 0) throw std::runtime_error(root["max_seconds"].where + ": expected >= 0");
  s.config_dir = relativeTo(dir, scalar(root, "config_dir"));
  for (const auto& item : listItems(root, "sequences")) s.sequences.push_back(readSequence(item, dir));
  for (const auto& item : listItems(root, "noise_models")) s.estimates.push_back(readEstimate(item));
  s.variants = readVariants(root);
  if (s.sequences.empty()) throw std::runtime_error(s.path + ": sequences: the suite names no sequence");
  if (s.comms.empty()) throw std::runtime_error(root["comm"].where + ": no comm model");
  for (const auto& c : s.comms)
    if (nameSafe(c) != c) throw std::runtime_error(root["comm"].where + ": '" + c + "' is not a comm model name");
  return s;
}

}  // namespace cosmo::suite
