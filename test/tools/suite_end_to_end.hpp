#pragma once
// The fixture of the suite's end-to-end tests: a folder of the test's own with its own simulator and scan caches,
// the tools found beside the test binary, and the test's suite (test/suite/ci_short.yaml) run once (into "<root>/a")
// for every test to compare with.
#include <dirent.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cosmo/suite/child_process.hpp"
#include "cosmo/common/whole_file.hpp"

namespace suite_e2e {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string output;
};

inline fs::path binDir() { return fs::read_symlink("/proc/self/exe").parent_path(); }

/// Runs a tool found beside this test, its output (stdout and stderr) captured.
inline Outcome runTool(const std::string& tool, const std::vector<std::string>& args) {
  static int n = 0;
  const fs::path log = fs::temp_directory_path() / ("cosmo_suite_e2e_" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(n++) + ".log");
  std::vector<std::string> argv{(binDir() / tool).string()};
  argv.insert(argv.end(), args.begin(), args.end());
  const cosmo::suite::ChildResult r = cosmo::suite::runChild(argv, log.string());
  Outcome out{r.exit_code, cosmo::readWholeFileOrEmpty(log)};
  fs::remove(log);
  return out;
}

/// How many processes have `text` in their command line (the jobs of a suite writing below a folder).
inline int processesMentioning(const std::string& text) {
  int n = 0;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos || name == std::to_string(::getpid())) continue;
    std::string cmd = cosmo::readWholeFileOrEmpty(e.path() / "cmdline");
    for (char& c : cmd)
      if (c == '\0') c = ' ';
    if (cmd.find(text) != std::string::npos && cmd.find("zombie") == std::string::npos) {
      const std::string stat = cosmo::readWholeFileOrEmpty(e.path() / "stat");
      const auto close = stat.rfind(')');
      if (close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z') ++n;
    }
  }
  return n;
}

/// Every file below `dir` (relative paths), the suite's record left out when `skip_record`.
inline std::vector<std::string> filesBelow(const fs::path& dir, bool skip_record) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && !(skip_record && e.path().filename() == "suite.json"))
      files.push_back(fs::relative(e.path(), dir).string());
  std::sort(files.begin(), files.end());
  return files;
}

/// `got` holds the same files as `want` (the suite's record aside), byte for byte.
inline void expectSameFiles(const fs::path& got, const fs::path& want) {
  const auto g = filesBelow(got, true), w = filesBelow(want, true);
  EXPECT_EQ(g, w) << got << " vs " << want;
  for (const auto& f : g) {
    if (std::find(w.begin(), w.end(), f) == w.end()) continue;
    EXPECT_TRUE(cosmo::readWholeFileOrEmpty(got / f) == cosmo::readWholeFileOrEmpty(want / f)) << f << " differs: " << got << " vs " << want;
  }
}

struct Group {
  std::string id, layout, seed;
};

class SuiteEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("cosmo_suite_e2e_" + std::to_string(::getpid())));
    fs::create_directories(*root_);
    ::setenv("COSMO_SIM_CACHE", (*root_ / "sim_cache").c_str(), 1);
    ::setenv("COSMO_SCAN_CACHE", (*root_ / "scan_cache").c_str(), 1);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    if (!::testing::Test::HasFailure()) fs::remove_all(*root_, ec);
    delete root_;
  }
  static const fs::path& root() { return *root_; }
  static std::string ciSuite() { return std::string(COSMO_SOURCE_DIR) + "/test/suite/ci_short.yaml"; }
  static std::vector<Group> groups() {
    return {{"ci_mcd_s2_odom-reference", "mcd", "2"}, {"ci_cu_s2_odom-reference", "cu-multi", "2"}};
  }
  static std::vector<std::string> suiteCommand(const fs::path& out, const std::vector<std::string>& extra) {
    std::vector<std::string> argv{(binDir() / "cosmo_suite").string(), ciSuite(), "--out", out.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }
  /// The sequence config cosmo_simulate makes for the test's suite in `layout` (a cache hit after the suite's run).
  static fs::path sequence(const std::string& layout) {
    const Outcome r = runTool("cosmo_simulate", {"--config", std::string(COSMO_SOURCE_DIR) + "/test/suite/suite_light_sim.yaml",
                                              "--layout", layout});
    EXPECT_EQ(r.status, 0) << r.output;
    const auto end = r.output.find_last_not_of('\n');
    return r.output.substr(r.output.rfind('\n', end) + 1, end - r.output.rfind('\n', end));
  }
  /// The test's suite run whole into <root>/a, once.
  static fs::path runA() {
    const fs::path a = root() / "a";
    if (!ran_a_) {
      ran_a_ = true;
      const double t0 = cosmo::suite::monotonicSeconds();
      const Outcome r = runTool("cosmo_suite", {ciSuite(), "--out", a.string(), "--jobs", "2"});
      a_seconds_ = cosmo::suite::monotonicSeconds() - t0;
      std::printf("%s", r.output.c_str());
      a_ok_ = r.status == 0;
    }
    EXPECT_TRUE(a_ok_) << "the suite's run failed (its output is above)";
    return a;
  }
  static double runASeconds() { return a_seconds_; }

  /// Moves the reference run aside (to <root>/a_ref) while a test writes another run into the same output folder
  /// (a dataset's metadata names its noise-model file, which lies in the output folder), and puts it back after.
  struct ReferenceAside {
    fs::path a, ref;
    ReferenceAside() : a(runA()), ref(root() / "a_ref") { fs::rename(a, ref); }
    ~ReferenceAside() {
      std::error_code ec;
      fs::remove_all(a, ec);
      fs::rename(ref, a, ec);
    }
  };

 private:
  static inline fs::path* root_ = nullptr;
  static inline bool ran_a_ = false, a_ok_ = false;
  static inline double a_seconds_ = 0.0;
};

}  // namespace suite_e2e
