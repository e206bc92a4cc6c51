// The simulator's config files (config/sim/*.yaml, the rostests' *_sim.yaml): every key is one its readers list
// (the X-macro field lists of the world, terrain, LiDAR and motion, and the top-level and trial keys), so a
// misspelt key stops the run naming the file, the section, the key and the nearest name instead of silently
// keeping a default.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>

#include "cosmo/sim/simulation_params.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using namespace cosmo::sim;
namespace fs = std::filesystem;

namespace {

/// The error message of loading `text` (empty: it loaded).
std::string loadError(const std::string& text) {
  const fs::path path = fs::temp_directory_path() / "cosmo_sim_config_keys.yaml";
  std::ofstream(path) << text;
  try {
    SimulationParams::load(path.string());
  } catch (const std::runtime_error& e) { return e.what(); }
  return "";
}

std::string ciConfig() { return cosmo::readWholeFileOrEmpty(fs::path(COSMO_SOURCE_DIR) / "config/sim/ci.yaml"); }

/// `text` with the first match of `pattern` replaced (the test fails if there is none).
std::string replaced(const std::string& text, const std::string& pattern, const std::string& with) {
  const std::regex re(pattern, std::regex::multiline);
  EXPECT_TRUE(std::regex_search(text, re)) << pattern;
  return std::regex_replace(text, re, with, std::regex_constants::format_first_only);
}

}  // namespace

TEST(SimConfigKeys, EveryShippedSimConfigLoads) {
  int files = 0;
  for (const fs::path dir : {fs::path(COSMO_SOURCE_DIR) / "config/sim", fs::path(COSMO_SOURCE_DIR) / "test/rostest"})
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() != ".yaml" ||
          (dir.filename() == "rostest" && name.find("_sim.yaml") == std::string::npos))
        continue;
      EXPECT_NO_THROW(SimulationParams::load(e.path().string())) << e.path();
      ++files;
    }
  EXPECT_GE(files, 5);
}

TEST(SimConfigKeys, AMisspeltKeyInAnySectionNamesTheSectionTheKeyAndTheNearestName) {
  const std::string ci = ciConfig();
  ASSERT_EQ(loadError(ci), "");
  struct Case {
    const char* pattern;  // a key as ci.yaml writes it
    const char* typo;     // the same line misspelt
    const char* key;      // what the message must name
    const char* nearest;
  };
  const Case cases[] = {
      {"^seed:", "sed:", "sed: unknown parameter", "seed"},
      {"^  blocks_x:", "  blocks_xx:", "world.blocks_xx: unknown parameter", "blocks_x"},
      {"^  model: os1_64", "  model: os1_64\n  beamz: 32", "lidar.beamz: unknown parameter", "beams"},
      {"^    platform:", "    platfrom:", ".platfrom: unknown parameter", "platform"},
  };
  for (const Case& c : cases) {
    const std::string error = loadError(replaced(ci, c.pattern, c.typo));
    EXPECT_NE(error.find(c.key), std::string::npos) << c.typo << " -> " << error;
    EXPECT_NE(error.find(std::string("did you mean '") + c.nearest + "'"), std::string::npos) << error;
    EXPECT_NE(error.find("cosmo_sim_config_keys.yaml"), std::string::npos) << error;
  }
}

TEST(SimConfigKeys, TerrainAndMotionSectionsRejectUnknownKeysToo) {
  const std::string ci = ciConfig();
  const std::string terrain = loadError(replaced(ci, "^world:\\n", "world:\n  terrain:\n    amplitud: 0.3\n"));
  EXPECT_NE(terrain.find("terrain.amplitud: unknown parameter (did you mean 'amplitude'?)"), std::string::npos)
      << terrain;
  const std::string motion =
      loadError(replaced(ci, "^  - robot: a\\n", "  - robot: a\n    motion:\n      cruise_sped: 1.0\n"));
  EXPECT_NE(motion.find("motion.cruise_sped: unknown parameter (did you mean 'cruise_speed'?)"), std::string::npos)
      << motion;
}
