// comm_simulate as a user runs it (found beside this test binary): --write-trace writes the distance model's own
// realization as a radio trace, and --trace replays it to the same transfers; a bad trace stops with file and line.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

using cosmo::test::binDir;

std::pair<int, std::string> runTool(const std::string& tool, const std::string& args) {
  const cosmo::test::CommandRun r = cosmo::test::runCommand("'" + (binDir() / tool).string() + "' " + args + " 2>&1");
  return {r.status, r.output};
}

/// The CSV without its last column (link: distance in the model run, trace in the replay).
std::string withoutLinkColumn(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, out;
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

class CommSimulateTrace : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(binDir() / "comm_simulate")) GTEST_SKIP() << "comm_simulate is not built beside this test";
    dir_ = fs::temp_directory_path() / ("cosmo_trace_tool_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // Three robots for 120 s: a and b pass each other, c circles between them (TUM: stamp x y z qx qy qz qw).
    for (char r : {'a', 'b', 'c'}) {
      std::ofstream out(dir_ / (std::string(1, r) + ".tum"));
      for (int i = 0; i <= 1200; ++i) {
        const double t = 0.1 * i;
        const double x = r == 'a' ? -80 + 1.4 * t : r == 'b' ? 80 - 1.3 * t : 30 * std::cos(0.04 * t);
        const double y = r == 'a' ? 0 : r == 'b' ? 6 : 30 * std::sin(0.04 * t);
        out << std::fixed << 1700000000.0 + (r == 'c' ? 5.0 : 0.0) + t << " " << x << " " << y << " 0 0 0 0 1\n";
      }
    }
    robots_ = "a=" + (dir_ / "a.tum").string() + " b=" + (dir_ / "b.tum").string() + " c=" + (dir_ / "c.tum").string();
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  fs::path dir_;
  std::string robots_;
};

}  // namespace

TEST_F(CommSimulateTrace, AWrittenTraceReplaysTheModelRunsDeliveriesExactly) {
  for (const std::string comm : {"wifi", "proradio"}) {
    const fs::path model = dir_ / (comm + "_model.csv"), replay = dir_ / (comm + "_replay.csv"),
                   trace = dir_ / (comm + "_trace.csv");
    auto [rc, out] = runTool("comm_simulate", "--comm " + comm +
                                                  " --seed 4 --kf-distance 3 --scan-points 30000 "
                                                  "--write-trace " +
                                                  trace.string() + " --out " + model.string() + " " + robots_);
    ASSERT_EQ(rc, 0) << out;
    std::tie(rc, out) = runTool("comm_simulate", "--comm " + comm +
                                                     " --seed 4 --kf-distance 3 --scan-points 30000 "
                                                     "--trace " +
                                                     trace.string() + " --out " + replay.string() + " " + robots_);
    ASSERT_EQ(rc, 0) << out;
    const std::string expected = withoutLinkColumn(model);
    EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 20) << "too few transfers to compare";
    EXPECT_EQ(withoutLinkColumn(replay), expected) << comm;
    std::ifstream js(dir_ / (comm + "_replay.summary.json"));
    const auto summary = nlohmann::json::parse(js);
    EXPECT_EQ(summary["trace"]["samples_from_distance_model"], 0) << comm;
    EXPECT_GT(summary["trace"]["samples_from_trace"].get<int>(), 0) << comm;
    EXPECT_EQ(summary["time_origin_ns"], 1700000000000000000ULL);
  }
}

TEST_F(CommSimulateTrace, ABadTraceStopsWithFileAndLine) {
  const fs::path bad = dir_ / "bad.csv";
  std::ofstream(bad) << "robot_a,robot_b,start,duration,throughput_Bps,latency,connected\na,b,0,1,100,0,1\n"
                        "a,d,0,1,100,0,1\n";
  const auto [rc, out] =
      runTool("comm_simulate", "--trace " + bad.string() + " --out " + (dir_ / "x.csv").string() + " " + robots_);
  EXPECT_EQ(rc, 1);
  EXPECT_NE(out.find(bad.string() + ":3: robot 'd' is not in the team (a, b, c)"), std::string::npos) << out;
}
