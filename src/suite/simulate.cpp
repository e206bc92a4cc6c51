#include "cosmo/suite/simulate.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cosmo/suite/child_process.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {

std::function<std::string(const SequenceEntry&)> simulateWith(const std::string& program_dir,
                                                              const std::string& log_dir) {
  return [program_dir, log_dir](const SequenceEntry& e) {
    const std::string log =
        (fs::path(log_dir) / ("simulate-" + fs::path(e.simulate).stem().string() + "-" + e.layout + ".log")).string();
    fs::remove(log);
    const ChildResult r = runChild(
        {(fs::path(program_dir) / "cosmo_simulate").string(), "--config", e.simulate, "--layout", e.layout}, log);
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    if (r.exit_code != 0 || !fs::exists(last))
      throw std::runtime_error(e.where + ": cosmo_simulate failed (" + r.describe() + "): " + tailOfFile(log, 5) +
                               "  (log: " + log + ")");
    return last;
  };
}

}  // namespace cosmo::suite
