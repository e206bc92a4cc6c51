#include "cosmo/sequence/built_in_sequence.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "cosmo/common/config_dir.hpp"
#include "cosmo/sim/simulation_params.hpp"

namespace cosmo::sequence {

BuiltInSequence builtInSequence(const std::string& simulate_config, const std::string& out,
                                const std::string& tools_dir) {
  BuiltInSequence s;
  s.simulate_config = simulate_config.empty() ? defaultConfigDir() + "/sim/default.yaml" : simulate_config;
  const std::string name = sim::SimulationParams::load(s.simulate_config).name;
  s.command = "'" + tools_dir + "/cosmo_simulate' --config '" + s.simulate_config + "' --out '" + out + "'";
  s.path = out + "/" + name + ".yaml";
  return s;
}

std::string writeBuiltInSequence(const BuiltInSequence& sequence) {
  if (std::system(sequence.command.c_str()) != 0)
    throw std::runtime_error("cosmo_simulate failed: " + sequence.command);
  return sequence.path;
}

std::string programDir() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec || self.empty() ? "." : self.parent_path().string();
}

}  // namespace cosmo::sequence
