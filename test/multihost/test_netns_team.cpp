// A robot per machine, emulated with network namespaces (scripts/netns_team.sh): the base in one namespace, each
// robot's front-end (and, with robot-side playback, its trial_player) in its own, with its own address, and the
// data hidden from it. A short lockstep run of the CI sequence (reference odometry, 30 s) with the player reading
// the trials on the base and with each robot reading its own: both JRLs must equal cosmo_generate's byte for
// byte. Prints the bytes per second each link carried. Then a robot whose nodes register an address the base
// cannot reach (a wrong ROS_IP): the run must stop naming it. Skipped (with the reason) without root or `ip netns`.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct NetnsRun {
  int exit_code = -1;
  std::string output, skip_reason;
  nlohmann::json summary;
};

const NetnsRun& netnsRun() {
  static NetnsRun run = [] {
    NetnsRun r;
    const std::string work = std::string(COSMO_DEVEL_PREFIX) + "/../netns_team";
    std::filesystem::remove_all(work);
    const std::string cmd = std::string("'") + COSMO_SOURCE_DIR + "/scripts/netns_team.sh' --devel '" +
                            COSMO_DEVEL_PREFIX + "' --work '" + work +
                            "' --playback base,robot --odometry reference --max-seconds 30 --timeout 400 --unreachable 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    char buffer[4096];
    while (pipe && fgets(buffer, sizeof buffer, pipe)) {
      r.output += buffer;
      std::cout << buffer << std::flush;
    }
    const int status = pipe ? pclose(pipe) : -1;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (r.exit_code == 77) r.skip_reason = r.output.substr(0, r.output.find('\n'));
    std::ifstream in(work + "/summary.json");
    if (in) r.summary = nlohmann::json::parse(in, nullptr, false);
    return r;
  }();
  return run;
}

void expectIdentical(const std::string& playback) {
  const NetnsRun& run = netnsRun();
  if (!run.skip_reason.empty()) GTEST_SKIP() << run.skip_reason;
  ASSERT_TRUE(run.summary.is_object() && run.summary.contains(playback))
      << "exit " << run.exit_code << ", no summary for playback " << playback << ":\n" << run.output;
  const nlohmann::json& s = run.summary[playback];
  EXPECT_EQ(s.value("exit", -1), 0) << "the base's launch failed";
  EXPECT_EQ(s.value("identical", false), true) << "the JRL differs from cosmo_generate's";
}

}  // namespace

TEST(NetnsTeam, BasePlaybackAcrossNamespacesWritesTheOfflineJrl) { expectIdentical("base"); }

TEST(NetnsTeam, RobotPlaybackAcrossNamespacesWritesTheOfflineJrl) { expectIdentical("robot"); }

TEST(NetnsTeam, RobotPlaybackKeepsTheRawScansOnTheRobots) {
  const NetnsRun& run = netnsRun();
  if (!run.skip_reason.empty()) GTEST_SKIP() << run.skip_reason;
  ASSERT_TRUE(run.summary.contains("base") && run.summary.contains("robot")) << run.output;
  for (const auto& [r, link] : run.summary["robot"]["links"].items()) {
    const double base = run.summary["base"]["links"][r].value("base_to_robot_bytes", 0.0);
    const double robot = link.value("base_to_robot_bytes", 0.0);
    EXPECT_LT(robot, 0.1 * base) << "link " << r << ": base -> robot carried " << robot << " B with the robot reading"
                                 << " its own trial, " << base << " B with the base reading it";
  }
}

TEST(NetnsTeam, ARobotNotReachableBackStopsTheRunNamingIt) {
  const NetnsRun& run = netnsRun();
  if (!run.skip_reason.empty()) GTEST_SKIP() << run.skip_reason;
  ASSERT_TRUE(run.summary.contains("unreachable")) << run.output;
  const nlohmann::json& u = run.summary["unreachable"];
  const std::string status = u.value("status", "");
  EXPECT_EQ(status.rfind("stopped: ", 0), 0u) << status;
  EXPECT_NE(status.find("/" + u.value("robot", "?") + "/frontend"), std::string::npos) << status;
  EXPECT_NE(status.find(u.value("address", "?")), std::string::npos) << status;
  EXPECT_NE(status.find("ROS_IP"), std::string::npos) << "the likely cause is not named: " << status;
}
