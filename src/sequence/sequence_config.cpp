#include "cosmo/sequence/sequence_config.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "cosmo/common/config.hpp"
#include "cosmo/common/pose_io.hpp"

namespace cosmo::sequence {

std::string resolvePath(const std::string& base_dir, const std::string& path) {
  if (path.empty()) return path;
  std::filesystem::path p(path);
  if (p.is_absolute() || base_dir.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

namespace {

char readRobotId(const ConfigNode& node, const std::string& key) {
  std::string id;
  node.read(key, id);
  if (id.size() != 1 || id[0] < 'a' || id[0] > 'z')
    throw std::runtime_error(node.where + "." + key + ": robot id must be one lower-case letter, got '" + id + "'");
  return id[0];
}

bool readStampAtEnd(const ConfigNode& t) {
  if (t.has("stamp_at_end")) throw std::runtime_error(t.where + ".stamp_at_end: use `stamp: end` or `stamp: start`");
  std::string stamp = "end";
  t.read("stamp", stamp);
  if (stamp != "end" && stamp != "start")
    throw std::runtime_error(t.where + ".stamp: expected start or end (the sweep instant of the header stamp), got '" +
                             stamp + "'");
  return stamp == "end";
}

ReferenceOffsetConfig readReferenceOffset(const ConfigNode& root) {
  ReferenceOffsetConfig r;
  if (!root.has("reference_offset")) return r;
  const YAML::Node n = root.node["reference_offset"];
  const std::string where = root.where + ": reference_offset";
  if (n.IsSequence()) {
    std::vector<double> v;
    root.read("reference_offset", v);
    if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw std::runtime_error(where + ": expected none, anchor or [x, y, z]");
    r.mode = ReferenceOffsetConfig::Mode::Fixed;
    r.fixed = Eigen::Vector3d(v[0], v[1], v[2]);
    return r;
  }
  std::string mode;
  root.read("reference_offset", mode);
  if (mode == "none") return r;
  if (mode != "anchor") throw std::runtime_error(where + ": expected none, anchor or [x, y, z], got '" + mode + "'");
  r.mode = ReferenceOffsetConfig::Mode::Anchor;
  return r;
}

/// The `registration:` section: a map of scalar values, checked against RegistrationParams here, so that a typo
/// stops the run when the sequence is read, naming this file.
std::map<std::string, std::string> readRegistration(const ConfigNode& root) {
  if (!root.has("registration")) return {};
  const ConfigNode section = root["registration"];
  std::map<std::string, std::string> keys = section.scalarMap("config/registration.yaml keys");
  registration::RegistrationParams::fromConfig(section);
  return keys;
}

}  // namespace

SequenceConfig SequenceConfig::load(const std::string& path, const std::string& data_root) {
  const ConfigNode root = ConfigNode::load(path);
  if (!root.node.IsMap()) throw std::runtime_error(path + ": expected a map with name, seed, anchor, trials");
  SequenceConfig cfg;
  cfg.path = path;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  std::string file_root;
  root.read("data_root", file_root);
  const char* env_root = std::getenv("COSMO_DATA_ROOT");
  if (!data_root.empty()) {
    cfg.data_root = resolvePath(std::filesystem::current_path().string(), data_root);
    cfg.data_root_from = "argument";
  } else if (!file_root.empty()) {
    cfg.data_root = resolvePath(dir, file_root);
    cfg.data_root_from = "data_root key";
  } else if (env_root && *env_root) {
    cfg.data_root = resolvePath(std::filesystem::current_path().string(), env_root);
    cfg.data_root_from = "COSMO_DATA_ROOT";
  } else {
    cfg.data_root = dir.empty() ? std::string(".") : dir;
    cfg.data_root_from = "config folder";
  }
  cfg.reference_offset = readReferenceOffset(root);
  cfg.registration = readRegistration(root);
  if (!root.has("name")) throw std::runtime_error(path + ": name: missing");
  root.read("name", cfg.name);
  if (cfg.name.empty()) throw std::runtime_error(path + ": name: empty");
  root.read("source", cfg.source);
  root.read("seed", cfg.seed);
  root.read("time_offset_sigma", cfg.time_offset_sigma);
  root.read("environment", cfg.environment);
  std::string noise;
  root.read("noise_models", noise);
  cfg.noise_models = resolvePath(dir, noise);
  if (!(cfg.time_offset_sigma >= 0.0)) throw std::runtime_error(path + ": time_offset_sigma: must be >= 0");

  if (!root.has("trials") || !root.node["trials"].IsSequence() || root.node["trials"].size() == 0)
    throw std::runtime_error(path + ": trials: missing or not a non-empty list");
  std::set<char> seen;
  const YAML::Node trials = root.node["trials"];
  for (std::size_t i = 0; i < trials.size(); ++i) {
    ConfigNode t{trials[i], path + ": trials[" + std::to_string(i) + "]"};
    if (!t.node.IsMap()) throw std::runtime_error(t.where + ": expected a map");
    TrialConfig trial;
    if (!t.has("robot")) throw std::runtime_error(t.where + ".robot: missing");
    trial.robot = readRobotId(t, "robot");
    if (!seen.insert(trial.robot).second)
      throw std::runtime_error(t.where + ".robot: robot '" + std::string(1, trial.robot) + "' listed twice");
    t.read("name", trial.name);
    if (trial.name.empty()) trial.name = std::string("robot_") + trial.robot;
    if (!t.has("bag")) throw std::runtime_error(t.where + ".bag: missing");
    std::string bag, reference;
    t.read("bag", bag);
    t.read("topic", trial.topic);
    t.read("reference", reference);
    trial.stamp_at_end = readStampAtEnd(t);
    trial.bag = resolvePath(cfg.data_root, bag);
    trial.reference = resolvePath(cfg.data_root, reference);
    if (t.has("extrinsic")) {
      std::vector<double> v;
      t.read("extrinsic", v);
      trial.extrinsic = parsePoseNumbers(v, t.where + ".extrinsic");
    }
    cfg.trials.push_back(trial);
  }
  if (root.has("anchor")) {
    cfg.anchor = readRobotId(root, "anchor");
  } else {
    cfg.anchor = cfg.trials.front().robot;
  }
  if (!seen.count(cfg.anchor))
    throw std::runtime_error(path + ": anchor: robot '" + std::string(1, cfg.anchor) + "' has no trial");
  return cfg;
}

registration::RegistrationParams SequenceConfig::registrationParams(const std::string& config_dir) const {
  return registrationParamsWith(config_dir, registration, path.empty() ? "sequence " + name : path);
}

registration::RegistrationParams registrationParamsWith(const std::string& config_dir,
                                                        const std::map<std::string, std::string>& keys,
                                                        const std::string& from) {
  const std::string file = (std::filesystem::path(config_dir) / "registration.yaml").string();
  YAML::Node merged(YAML::NodeType::Map);
  std::string where = "compiled-in defaults";
  if (std::filesystem::exists(file)) {
    const ConfigNode loaded = ConfigNode::load(file);
    const ConfigNode section = loaded.has("registration") ? loaded["registration"] : loaded;
    if (section.node.IsMap()) merged = YAML::Clone(section.node);
    where = section.where;
  }
  for (const auto& [key, value] : keys) merged[key] = value;
  if (!keys.empty()) where += " with " + from + ": registration";
  return registration::RegistrationParams::fromConfig(ConfigNode{merged, where});
}

std::vector<char> SequenceConfig::robots() const {
  std::vector<char> r;
  for (const auto& t : trials) r.push_back(t.robot);
  return r;
}

const TrialConfig& SequenceConfig::trial(char robot) const {
  for (const auto& t : trials)
    if (t.robot == robot) return t;
  throw std::runtime_error((path.empty() ? std::string("sequence ") + name : path) + ": no trial for robot '" +
                           std::string(1, robot) + "'");
}

}  // namespace cosmo::sequence
