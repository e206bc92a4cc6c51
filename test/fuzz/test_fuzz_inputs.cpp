// Every fuzz target (fuzz/targets/*.cpp, built here without libFuzzer) on the inputs kept in the repository:
// its seeds (fuzz/corpus/<target> and the folders of fuzz/seed_dirs.txt) must be read without error — a target
// whose valid inputs fail would fuzz nothing — and its regression inputs (fuzz/regressions/<target>: inputs that
// once crashed a reader) must end with a message or be read, never with a crash or another exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../../fuzz/fuzz_target.hpp"

namespace fs = std::filesystem;
using cosmo::fuzz::targets;

namespace {

const fs::path kRoot = COSMO_SOURCE_DIR;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<fs::path> filesIn(const fs::path& dir, const std::string& extension = "") {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// The seeds of `target`: fuzz/corpus/<target> and its lines of fuzz/seed_dirs.txt.
std::vector<fs::path> seedsOf(const std::string& target) {
  std::vector<fs::path> seeds = filesIn(kRoot / "fuzz" / "corpus" / target);
  std::ifstream list(kRoot / "fuzz" / "seed_dirs.txt");
  std::string line;
  while (std::getline(list, line)) {
    std::istringstream words(line);
    std::string name, extension, dir;
    if (!(words >> name >> extension) || name != target) continue;
    while (words >> dir)
      for (const auto& f : filesIn(kRoot / dir, extension)) seeds.push_back(f);
  }
  return seeds;
}

bool run(const std::string& target, const fs::path& input, std::string& message) {
  const std::string bytes = slurp(input);
  return cosmo::fuzz::runInput(targets().at(target), reinterpret_cast<const std::uint8_t*>(bytes.data()),
                               bytes.size(), &message);
}

}  // namespace

TEST(FuzzInputs, EveryTargetHasSeedsThatItReads) {
  ASSERT_GE(targets().size(), 10u);
  for (const auto& [target, fn] : targets()) {
    const auto seeds = seedsOf(target);
    EXPECT_FALSE(seeds.empty()) << target << ": no seed";
    for (const auto& seed : seeds) {
      std::string message;
      EXPECT_TRUE(run(target, seed, message)) << target << " " << seed << ": " << message;
    }
  }
}

TEST(FuzzInputs, RegressionInputsEndWithAMessage) {
  std::size_t inputs = 0;
  for (const auto& dir : filesIn(kRoot / "fuzz" / "regressions")) ADD_FAILURE() << "not a folder: " << dir;
  for (const auto& e : fs::directory_iterator(kRoot / "fuzz" / "regressions")) {
    const std::string target = e.path().filename().string();
    ASSERT_TRUE(targets().count(target)) << "fuzz/regressions/" << target << ": no such target";
    for (const auto& input : filesIn(e.path())) {
      std::string message;
      ++inputs;
      try {
        if (!run(target, input, message)) EXPECT_FALSE(message.empty()) << target << " " << input;
      } catch (const std::exception& ex) {
        ADD_FAILURE() << target << " " << input << ": " << typeid(ex).name() << ": " << ex.what();
      }
    }
  }
  std::cout << inputs << " regression inputs replayed\n";
}
