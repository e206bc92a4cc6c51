// Connectivity over a radio run (comm/connectivity.hpp): a scripted link gives its exact connected time,
// disconnections, bytes, intervals and windows; the radio's own steps follow LinkModel::connected (d_init, a trace
// window, robots off); the JSON is the same bytes for the same run and reads back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "cosmo/comm/connectivity.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;

namespace {

/// Robots a, b, c; 100 steps of 0.1 s ending at 0.1 ... 10.0 s. ab up in steps 1-30 and 51-80, 1000 bytes through
/// in steps 1-40; ac never up; bc up throughout; c off in steps 1-10.
comm::Connectivity scriptedRun() {
  comm::ConnectivityTracker tracker({'c', 'b', 'a'}, 0.1, 1.0);
  for (int i = 1; i <= 100; ++i) {
    if (i <= 40) tracker.addBytes('b', 'a', 1000.0);
    if (i == 20) {
      comm::Transfer x;
      x.sender = 'a';
      x.receiver = 'b';
      tracker.addTransfer(x);
      x.sender = 'b';
      x.receiver = 'a';
      x.outcome = comm::Transfer::Outcome::TimedOut;
      tracker.addTransfer(x);
      tracker.addTransfer(x);
    }
    const bool ab = (i >= 1 && i <= 30) || (i >= 51 && i <= 80);
    tracker.endStep(
        0.1 * i, [&](char a, char b) { return a == 'a' && b == 'b' ? ab : a == 'b' && b == 'c'; },
        [&](char r) { return r != 'c' || i > 10; });
  }
  return tracker.result();
}

}  // namespace

TEST(Connectivity, ScriptedLinkGivesExactFigures) {
  const comm::Connectivity c = scriptedRun();
  EXPECT_EQ(c.robots, "abc");
  EXPECT_EQ(c.steps, 100u);
  EXPECT_DOUBLE_EQ(c.runSeconds(), 10.0);
  EXPECT_NEAR(c.start_s, 0.0, 1e-12);
  EXPECT_NEAR(c.end_s, 10.0, 1e-12);
  ASSERT_EQ(c.pairs.size(), 3u);
  const comm::PairConnectivity &ab = c.pairs[0], &ac = c.pairs[1], &bc = c.pairs[2];
  EXPECT_EQ(std::string({ab.a, ab.b, ac.a, ac.b, bc.a, bc.b}), "abacbc");

  EXPECT_DOUBLE_EQ(ab.connected_s, 6.0);
  EXPECT_DOUBLE_EQ(c.connectedFraction(ab), 0.6);
  EXPECT_EQ(ab.disconnections, 2u);
  EXPECT_DOUBLE_EQ(ab.both_on_s, 10.0);
  ASSERT_EQ(ab.up.size(), 2u);
  EXPECT_NEAR(ab.up[0].first, 0.0, 1e-9);
  EXPECT_NEAR(ab.up[0].second, 3.0, 1e-9);
  EXPECT_NEAR(ab.up[1].first, 5.0, 1e-9);
  EXPECT_NEAR(ab.up[1].second, 8.0, 1e-9);
  EXPECT_DOUBLE_EQ(ab.bytes, 40000.0);
  EXPECT_DOUBLE_EQ(ab.bytes_connected, 30000.0);
  EXPECT_DOUBLE_EQ(ab.throughputConnectedBps(), 5000.0);
  EXPECT_EQ(ab.delivered_ab, 1u);
  EXPECT_EQ(ab.delivered_ba, 0u);
  EXPECT_EQ(ab.dropped_ab, 0u);
  EXPECT_EQ(ab.dropped_ba, 2u);
  ASSERT_EQ(ab.window_Bps.size(), 10u);
  for (int k = 0; k < 10; ++k) EXPECT_DOUBLE_EQ(ab.window_Bps[k], k < 4 ? 10000.0 : 0.0) << k;

  EXPECT_DOUBLE_EQ(ac.connected_s, 0.0);
  EXPECT_EQ(ac.disconnections, 0u);
  EXPECT_TRUE(ac.up.empty());
  EXPECT_DOUBLE_EQ(ac.throughputConnectedBps(), 0.0);
  EXPECT_NEAR(ac.both_on_s, 9.0, 1e-9);

  EXPECT_DOUBLE_EQ(bc.connected_s, 10.0);  // connected as told; the radio's rule says both must be on
  EXPECT_EQ(bc.disconnections, 0u);        // up at the end of the run is no disconnection
  ASSERT_EQ(bc.up.size(), 1u);

  // robots in range: ab + bc per window (window k holds steps 10k+1 .. 10k+10)
  ASSERT_EQ(c.pairs_connected.size(), 10u);
  const double expected[10] = {2, 2, 2, 1, 1, 2, 2, 2, 1, 1};
  for (int k = 0; k < 10; ++k) EXPECT_DOUBLE_EQ(c.pairs_connected[k], expected[k]) << k;
}

TEST(Connectivity, JsonIsRoundedDeterministicAndReadsBack) {
  const comm::Connectivity c = scriptedRun();
  const std::string text = c.toJson().dump();
  EXPECT_EQ(scriptedRun().toJson().dump(), text);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["pairs"][0]["robots"], "ab");
  EXPECT_EQ(j["pairs"][0]["connected_fraction"].get<double>(), 0.6);
  EXPECT_EQ(j["pairs"][0]["delivered"]["a>b"], 1);
  EXPECT_EQ(j["pairs"][0]["dropped"]["b>a"], 2);
  EXPECT_EQ(j["pairs"][0]["up"].dump(), "[[0.0,3.0],[5.0,8.0]]");
  EXPECT_EQ(j["run_s"].get<double>(), 10.0);
  const comm::Connectivity back = comm::Connectivity::fromJson(j, "test");
  EXPECT_EQ(back.toJson().dump(), text);
  EXPECT_THROW(comm::Connectivity::fromJson(nlohmann::json::object(), "x.json"), std::runtime_error);
}

TEST(Connectivity, PathBesideTheTransferLog) {
  EXPECT_EQ(comm::connectivityPath("/o/seq_wifi_transfers.csv"), "/o/seq_wifi_connectivity.json");
  EXPECT_EQ(comm::connectivityPath("/o/transfers.csv"), "/o/transfers_connectivity.json");
  EXPECT_EQ(comm::connectivityPath("log"), "log_connectivity.json");
  EXPECT_EQ(comm::datasetConnectivityPath("/o/seq_wifi.jrl"), "/o/seq_wifi_connectivity.json");
}

// The radio's steps: within d_init (Wi-Fi 30 m) connected, beyond not, a robot off never, and a trace window's
// `connected` wins over the distance.
TEST(Connectivity, RadioFollowsLinkModelConnected) {
  comm::RadioParams p = comm::RadioParams::wifi();
  std::istringstream trace(
      "robot_a,robot_b,start,duration,throughput_Bps,latency,connected\n"
      "a,c,0.0,2.0,1000,0,0\n");
  p.trace = std::make_shared<const comm::RadioTrace>(comm::RadioTrace::parse(trace, "t.csv"));
  comm::RadioSimulator sim(p, {'a', 'b', 'c'}, 3);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {10, 0, 0}, true);
  sim.setRobotState('c', {5, 0, 0}, false);
  for (int i = 0; i < 10; ++i) sim.step(sim.nextStepTime());  // 0.0 .. 0.9: ab up
  sim.setRobotState('b', {40, 0, 0}, true);
  sim.setRobotState('c', {5, 0, 0}, true);
  for (int i = 0; i < 20; ++i) sim.step(sim.nextStepTime());  // 1.0 .. 2.9: ab down; ac down in the window, then up
  sim.setRobotState('b', {29, 0, 0}, true);
  for (int i = 0; i < 10; ++i) sim.step(sim.nextStepTime());  // 3.0 .. 3.9: ab up again

  const comm::Connectivity c = sim.connectivity();
  EXPECT_EQ(c.steps, 40u);
  EXPECT_EQ(c.trace, "t.csv");
  EXPECT_DOUBLE_EQ(c.d_init, 30.0);
  const comm::PairConnectivity &ab = c.pairs[0], &ac = c.pairs[1], &bc = c.pairs[2];
  EXPECT_NEAR(ab.connected_s, 2.0, 1e-9);
  EXPECT_EQ(ab.disconnections, 1u);
  ASSERT_EQ(ab.up.size(), 2u);
  EXPECT_NEAR(ab.up[1].first, 2.9, 1e-9);
  // ac: c off for 10 steps, then the trace's window (steps at 1.0 .. 2.0: middles before 2.0) says down, then 5 m
  EXPECT_NEAR(ac.both_on_s, 3.0, 1e-9);
  EXPECT_NEAR(ac.connected_s, 1.9, 1e-9);
  EXPECT_EQ(ac.disconnections, 0u);
  // bc: 35 m, then 24 m
  EXPECT_NEAR(bc.connected_s, 1.0, 1e-9);
}

TEST(Connectivity, TransferLogWritesItBesideTheCsvTheSameBytesEachRun) {
  const auto dir = std::filesystem::temp_directory_path() / ("cosmo_connectivity_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string first;
  for (int run = 0; run < 2; ++run) {
    comm::RadioSimulator sim(comm::RadioParams::proRadio(), {'a', 'b'}, 7);
    sim.setTimeOrigin(1700000000000000000ULL);
    sim.setRobotState('a', {0, 0, 0}, true);
    for (std::size_t k = 0; k < 20; ++k) {
      sim.offerKeyframe('a', k, 200000);
      sim.offerKeyframe('b', k, 200000);
    }
    for (int i = 0; i < 300; ++i) {
      sim.setRobotState('b', {i < 150 ? 100.0 : 180.0, 0, 0}, true);
      sim.step(sim.nextStepTime());
    }
    const std::string csv = (dir / "demo_proradio_transfers.csv").string();
    writeTransferLog(csv, sim);
    const std::string text = readWholeFileOrEmpty((dir / "demo_proradio_connectivity.json").string());
    ASSERT_FALSE(text.empty());
    if (run == 0) first = text;
    EXPECT_EQ(text, first);
    const comm::Connectivity c = comm::Connectivity::read((dir / "demo_proradio_connectivity.json").string());
    EXPECT_EQ(c.time_origin_ns, 1700000000000000000ULL);
    ASSERT_EQ(c.pairs.size(), 1u);
    EXPECT_NEAR(c.pairs[0].connected_s, 15.0, 1e-3);
    EXPECT_EQ(c.pairs[0].disconnections, 1u);
    EXPECT_EQ(c.pairs[0].delivered_ab + c.pairs[0].delivered_ba, sim.stats().delivered);
    EXPECT_EQ(c.pairs[0].dropped_ab + c.pairs[0].dropped_ba, sim.stats().timed_out);
    EXPECT_NEAR(c.pairs[0].bytes, sim.stats().bytes_transmitted, 1.0);
    EXPECT_GT(c.pairs[0].throughputConnectedBps(), 0.0);
  }
  std::filesystem::remove_all(dir);
}
