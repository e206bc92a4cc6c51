#include "cosmo/common/config.hpp"

namespace cosmo {

ConfigNode ConfigNode::load(const std::string& path) {
  try {
    return ConfigNode{YAML::LoadFile(path), path + ": "};
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(path + ": cannot open config file");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ": malformed YAML: " + e.what());
  }
}

ConfigNode ConfigNode::operator[](const std::string& key) const {
  ConfigNode child;
  if (has(key)) child.node = node[key];
  const bool root = !where.empty() && where.back() == ' ';
  child.where = where + (root || where.empty() ? "" : ".") + key;
  return child;
}

}  // namespace cosmo
