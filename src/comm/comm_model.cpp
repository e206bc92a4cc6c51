#include "cosmo/comm/comm_model.hpp"

#include <filesystem>
#include <memory>

#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/common/config.hpp"

namespace fs = std::filesystem;

namespace cosmo::comm {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

CommModel resolveCommModel(const std::string& comm, const std::string& config_dir) {
  CommModel m;
  if (endsWith(comm, ".yaml")) {
    m.label = fs::path(comm).stem().string();
    m.file = comm;
    m.params = RadioParams::fromConfig(ConfigNode::load(comm));
    return m;
  }
  if (endsWith(comm, ".csv")) {
    m = resolveCommModel("wifi", config_dir);
    m.label = fs::path(comm).stem().string();
    m.trace = comm;
    m.params.trace = std::make_shared<const RadioTrace>(RadioTrace::read(comm));
    return m;
  }
  m.label = comm == "pro-radio" || comm == "pro_radio" ? "proradio" : comm;
  const fs::path file = config_dir.empty() ? fs::path() : fs::path(config_dir) / "comm" / (m.label + ".yaml");
  if (!file.empty() && fs::exists(file)) {
    m.file = file.string();
    m.params = RadioParams::fromConfig(ConfigNode::load(m.file));
  } else {
    m.params = RadioParams::byName(m.label);
  }
  return m;
}

}  // namespace cosmo::comm
