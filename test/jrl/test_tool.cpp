// The cosmo_jrl command-line tool (found beside this test binary): output and exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cosmo/common/shared_data.hpp"
#include "../support/run_command.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;

namespace {

std::string toolPath() {
  const fs::path tool = cosmo::test::binDir() / "cosmo_jrl";
  return fs::exists(tool) ? tool.string() : "";
}

/// Runs the tool with `args`; returns {exit code, stdout}.
std::pair<int, std::string> run(const std::string& args) {
  const cosmo::test::CommandRun r = cosmo::test::runCommand("'" + toolPath() + "' " + args + " 2>/dev/null");
  return {r.status, r.output};
}

const std::string kTiny = std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl";

}  // namespace

TEST(CosmoJrlTool, StatsValidateAndExitCodes) {
  if (toolPath().empty()) GTEST_SKIP() << "cosmo_jrl is not built beside this test";
  auto [rc, out] = run("stats " + kTiny);
  EXPECT_EQ(rc, 0);
  EXPECT_NE(out.find("tiny_example"), std::string::npos) << out;
  EXPECT_NE(out.find("LC        1 (100.0 %)"), std::string::npos) << out;
  std::tie(rc, out) = run("stats --json " + kTiny);
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(out.rfind("{", 0), 0u) << out;
  EXPECT_NE(out.find("\"irlc_count\":1"), std::string::npos) << out;
  std::tie(rc, out) = run("validate " + kTiny);
  EXPECT_EQ(rc, 0) << out;
  EXPECT_EQ(run("--help").first, 0);
  EXPECT_EQ(run("").first, 2);
  EXPECT_EQ(run("stats").first, 2);
  EXPECT_EQ(run("frobnicate x").first, 2);
  EXPECT_EQ(run("stats /nonexistent/x.jrl").first, 1);

  // An invalid dataset: validate prints the violation with its place and exits 1.
  const fs::path bad = fs::temp_directory_path() / ("cosmo_tool_bad_" + std::to_string(::getpid()) + ".jrl");
  {
    std::string text = cosmo::readWholeFileOrEmpty(kTiny);
    text.replace(text.find("\"stamp\":1700000000750000000"), 27, "\"stamp\":1");
    std::ofstream(bad) << text;
  }
  std::tie(rc, out) = run("validate " + bad.string());
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find("measurements.b[1].stamp: stamp 1 is before the previous entry's"), std::string::npos) << out;
  fs::remove(bad);
}

TEST(CosmoJrlTool, ReferenceStats) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  if (toolPath().empty()) GTEST_SKIP() << "cosmo_jrl is not built beside this test";
  const auto [rc, out] = run("stats " + *path);
  EXPECT_EQ(rc, 0);
  for (const char* want : {"duration  12:06", "length    2.13 km", "LC        356 (13.5 %)", "IRLC      280 (9.6 %)"})
    EXPECT_NE(out.find(want), std::string::npos) << want << "\n" << out;
}

TEST(CosmoJrlTool, SolvePlotAndExport) {
  if (toolPath().empty()) GTEST_SKIP() << "cosmo_jrl is not built beside this test";
  auto [rc, out] = run("solve --json " + kTiny);
  EXPECT_EQ(rc, 0) << out;
  for (const char* key :
       {"\"init_ate_m\":", "\"all_ate_m\":", "\"robust_ate_m\":", "\"inliers_ate_m\":", "\"robots\":{\"a\":{"})
    EXPECT_NE(out.find(key), std::string::npos) << key << "\n" << out;
  std::tie(rc, out) = run("solve " + kTiny);
  EXPECT_EQ(rc, 0);
  EXPECT_NE(out.find("inliers   ATE "), std::string::npos) << out;

  const fs::path dir = fs::temp_directory_path() / ("cosmo_tool_out_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::tie(rc, out) = run("plot --no-png -o " + dir.string() + " " + kTiny);
  EXPECT_EQ(rc, 0) << out;
  EXPECT_TRUE(fs::exists(dir / "tiny_example.trajectories.svg"));
  EXPECT_TRUE(fs::exists(dir / "tiny_example.frontend.svg"));
  std::tie(rc, out) = run("export " + kTiny + " --g2o " + (dir / "g.g2o").string() + " --tum " +
                          (dir / "tum").string() + " --labels " + (dir / "labels.csv").string());
  EXPECT_EQ(rc, 0) << out;
  EXPECT_TRUE(fs::exists(dir / "g.g2o"));
  for (const char* beside : {"g.blocks.csv", "g.ids.csv"}) {
    EXPECT_TRUE(fs::exists(dir / beside)) << beside;
    EXPECT_NE(out.find("wrote " + (dir / beside).string() + "\n"), std::string::npos) << out;
  }
  EXPECT_TRUE(fs::exists(dir / "tum" / "tiny_example_b_groundtruth.tum"));
  EXPECT_TRUE(fs::exists(dir / "labels.csv"));
  EXPECT_EQ(run("export " + kTiny).first, 2);
  EXPECT_EQ(run("plot -o").first, 2);
  EXPECT_EQ(run("solve /nonexistent/x.jrl").first, 1);
  fs::remove_all(dir);
}

TEST(CosmoJrlTool, InjectWritesAValidLabelledDatasetAndRejectsBadOptions) {
  if (toolPath().empty()) GTEST_SKIP() << "cosmo_jrl is not built beside this test";
  const fs::path dir = fs::temp_directory_path() / ("cosmo_tool_inject_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out_jrl = (dir / "tiny_50_random.jrl").string();
  auto [rc, out] = run("inject " + kTiny + " " + out_jrl + " --rate 0.5 --kind random --seed 3");
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("injected 2 random outliers"), std::string::npos) << out;  // 2 closures -> 2 of 4
  std::tie(rc, out) = run("validate " + out_jrl);
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = run("stats " + out_jrl);
  EXPECT_NE(out.find("tiny_50_random"), std::string::npos) << out;
  const std::string first = out;
  EXPECT_EQ(run("inject " + kTiny + " " + out_jrl + " --rate 0.5 --kind random --seed 3").first, 0);
  EXPECT_EQ(run("stats " + out_jrl).second, first);                                        // same seed, same dataset
  EXPECT_EQ(run("inject " + kTiny + " " + out_jrl + " --kind random --seed 3").first, 2);  // no --rate
  EXPECT_EQ(run("inject " + kTiny + " " + out_jrl + " --rate 0.5 --kind wrong --seed 3").first, 2);
  EXPECT_EQ(run("inject " + kTiny + " " + out_jrl + " --rate 0.5 --intra --inter --seed 3").first, 2);
  EXPECT_EQ(run("inject " + kTiny + " " + out_jrl + " --rate 1.5 --seed 3").first, 2);
  EXPECT_EQ(run("inject /nonexistent.jrl " + out_jrl + " --rate 0.5 --seed 3").first, 2);
  EXPECT_EQ(run("inject --help").first, 0);
  fs::remove_all(dir);
}
