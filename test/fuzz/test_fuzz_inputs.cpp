// Every fuzz target (fuzz/targets/*.cpp, built here without libFuzzer) on the inputs kept in the repository:
// its seeds (fuzz/seeds/<target> and the folders of fuzz/seed_dirs.txt) must be read without error — a target
// whose valid inputs fail would fuzz nothing — and its kept corpus (fuzz/corpus/<target>: what the campaigns found,
// mostly damaged inputs) and regression inputs (fuzz/regressions/<target>: inputs that once crashed a reader) must
// end with a message or be read, never with a crash or another exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../../fuzz/fuzz_target.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;
using cosmo::fuzz::targets;

namespace {

const fs::path kRoot = COSMO_SOURCE_DIR;

std::vector<fs::path> filesIn(const fs::path& dir, const std::string& extension = "") {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// The seeds of `target`: fuzz/seeds/<target> and its lines of fuzz/seed_dirs.txt.
std::vector<fs::path> seedsOf(const std::string& target) {
  std::vector<fs::path> seeds = filesIn(kRoot / "fuzz" / "seeds" / target);
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
  const std::string bytes = cosmo::readWholeFileOrEmpty(input);
  return cosmo::fuzz::runInput(targets().at(target), reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                               &message);
}

/// Every input of fuzz/<folder>/<target>/ ends with a message or is read; returns how many there are.
std::size_t replayEndsWithAMessage(const std::string& folder) {
  std::size_t inputs = 0;
  const fs::path root = kRoot / "fuzz" / folder;
  if (!fs::is_directory(root)) return 0;
  for (const auto& file : filesIn(root)) ADD_FAILURE() << "not a folder: " << file;
  for (const auto& e : fs::directory_iterator(root)) {
    if (!e.is_directory()) continue;
    const std::string target = e.path().filename().string();
    EXPECT_TRUE(targets().count(target)) << "fuzz/" << folder << "/" << target << ": no such target";
    if (!targets().count(target)) continue;
    for (const auto& input : filesIn(e.path())) {
      std::string message;
      ++inputs;
      try {
        if (!run(target, input, message)) { EXPECT_FALSE(message.empty()) << target << " " << input; }
      } catch (const std::exception& ex) {
        ADD_FAILURE() << target << " " << input << ": " << typeid(ex).name() << ": " << ex.what();
      }
    }
  }
  return inputs;
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
  std::cout << replayEndsWithAMessage("regressions") << " regression inputs replayed\n";
}

TEST(FuzzInputs, KeptCorpusEndsWithAMessage) {
  std::cout << replayEndsWithAMessage("corpus") << " inputs of the kept corpus replayed\n";
}

// scripts/fuzz.sh keeps inputs up to 64 KiB, at most 2 MiB per target (COSMO_FUZZ_MAX_INPUT, COSMO_FUZZ_BUDGET):
// a campaign run with other limits must not commit more.
TEST(FuzzInputs, KeptCorpusIsWithinItsBudget) {
  const fs::path root = kRoot / "fuzz" / "corpus";
  if (!fs::is_directory(root)) return;
  for (const auto& e : fs::directory_iterator(root)) {
    std::uintmax_t bytes = 0;
    for (const auto& input : filesIn(e.path())) {
      EXPECT_LE(fs::file_size(input), 65536u) << input;
      bytes += fs::file_size(input);
    }
    EXPECT_LE(bytes, 2097152u) << e.path();
  }
}
