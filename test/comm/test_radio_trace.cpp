// Radio traces (comm/radio_trace.hpp, comm/link_model.hpp): the CSV and its checks, a recorded run replayed
// exactly, a blackout window without deliveries, latency, and the fallback to phi(d) outside the windows.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>

#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/transfer_log.hpp"

using namespace cosmo;

namespace {

const std::string kBlackout = std::string(COSMO_SOURCE_DIR) + "/test/comm/data/blackout_3robots.csv";

comm::RadioTrace parse(const std::string& text, const std::string& source = "x.csv") {
  std::istringstream in(text);
  return comm::RadioTrace::parse(in, source);
}

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const std::exception& e) { return e.what(); }
  return "no error";
}

using Positions = std::function<Eigen::Vector3d(char robot, double t)>;

/// Runs `sim` from 0 to `seconds`: robots placed by `where`, each offering a keyframe of 150-300 kB every 2 s.
void run(comm::RadioSimulator& sim, double seconds, const Positions& where) {
  std::map<char, std::size_t> next;
  for (double t = sim.nextStepTime(); t <= seconds + 1e-9; t = sim.nextStepTime()) {
    for (char r : sim.robots()) {
      sim.setRobotState(r, where(r, t), true);
      if (t >= 2.0 * static_cast<double>(next[r])) {
        const std::size_t k = next[r]++;
        sim.offerKeyframe(r, k, 150000 + 1000 * ((k * 37 + static_cast<std::size_t>(r)) % 150));
      }
    }
    sim.step(t);
  }
}

/// Three robots that meet and part: a and b pass each other, c circles between them.
Eigen::Vector3d crossing(char r, double t) {
  if (r == 'a') return {-60.0 + 1.5 * t, 0.0, 0.0};
  if (r == 'b') return {60.0 - 1.2 * t, 5.0, 0.0};
  return {25.0 * std::cos(0.05 * t), 25.0 * std::sin(0.05 * t), 0.0};
}

std::string withoutLink(const std::vector<comm::Transfer>& transfers) {
  std::vector<comm::Transfer> copy = transfers;
  for (comm::Transfer& x : copy) x.link = comm::Transfer::Link::Distance;
  std::ostringstream out;
  writeTransferCsv(out, copy);
  return out.str();
}

}  // namespace

TEST(RadioTrace, ParsesWindowsAndFindsTheOneContainingATime) {
  const comm::RadioTrace t = parse(
      "# a comment\n\nrobot_a,robot_b,start,duration,throughput_Bps,latency,connected\n"
      "b,a,0,1.5,1000,0.01,1\n a , b , 1.5 , 0.5 , 0 , 0 , 0 \nb,c,3,1,2e6,0,1\n");
  EXPECT_EQ(t.windowCount(), 3u);
  ASSERT_NE(t.find('a', 'b', 0.0), nullptr);
  EXPECT_EQ(t.find('a', 'b', 1.49)->line, 4u);  // the row's own line
  EXPECT_TRUE(t.find('b', 'a', 1.49)->connected);
  EXPECT_EQ(t.find('a', 'b', 1.5)->line, 5u);
  EXPECT_FALSE(t.find('a', 'b', 1.7)->connected);
  EXPECT_EQ(t.find('a', 'b', 2.0), nullptr);   // after the last window of a-b
  EXPECT_EQ(t.find('a', 'b', -0.1), nullptr);  // before the first
  EXPECT_EQ(t.find('a', 'c', 0.5), nullptr);   // a pair without rows
  EXPECT_DOUBLE_EQ(t.find('c', 'b', 3.5)->throughput_Bps, 2e6);
  std::ostringstream out;
  t.write(out);
  EXPECT_EQ(parse(out.str()).windows().size(), 3u);
  EXPECT_NO_THROW(comm::RadioTrace::read(kBlackout));
}

TEST(RadioTrace, BadRowsStopWithFileAndLine) {
  const std::string h = "robot_a,robot_b,start,duration,throughput_Bps,latency,connected\n";
  EXPECT_EQ(errorOf(h + "a,b,0,1,-5,0,1\n"), "x.csv:2: throughput_Bps must be >= 0, got -5");
  EXPECT_EQ(errorOf(h + "a,b,0,2,5,0,1\n# gap\nb,a,1.5,1,5,0,1\n"),
            "x.csv:4: window [1.500000, 2.500000) of a-b overlaps [0.000000, 2.000000) at line 2");
  EXPECT_EQ(errorOf(h + "a,b,0,1,5,-0.1,1\n"), "x.csv:2: latency must be >= 0, got -0.1");
  EXPECT_EQ(errorOf(h + "a,b,0,0,5,0,1\n"), "x.csv:2: duration must be > 0, got 0");
  EXPECT_EQ(errorOf(h + "a,b,0,1,5,0,yes\n"), "x.csv:2: connected must be 0 or 1, got 'yes'");
  EXPECT_EQ(errorOf(h + "a,a,0,1,5,0,1\n"), "x.csv:2: robot_a and robot_b are both 'a'");
  EXPECT_EQ(errorOf(h + "ab,b,0,1,5,0,1\n"), "x.csv:2: robot_a: 'ab' is not a one-character robot id");
  EXPECT_EQ(errorOf(h + "a,b,0,1,fast,0,1\n"), "x.csv:2: throughput_Bps: 'fast' is not a finite number");
  EXPECT_EQ(errorOf(h + "a,b,0,1,5,0\n"),
            "x.csv:2: expected 7 columns (robot_a,robot_b,start,duration,throughput_Bps,latency,connected), got 6");
  EXPECT_EQ(errorOf("a,b,0,1,5,0,1\n").rfind("x.csv:1: expected the header", 0), 0u);
  EXPECT_EQ(errorOf("# nothing\n"), "x.csv: no header line 'robot_a,robot_b,start,duration,throughput_Bps,latency,connected'");

  comm::RadioParams p = comm::RadioParams::wifi();
  p.trace = std::make_shared<const comm::RadioTrace>(parse(h + "a,b,0,1,5,0,1\n\nb,d,0,1,5,0,1\n"));
  try {
    comm::RadioSimulator sim(p, {'a', 'b', 'c'}, 1);
    FAIL() << "a robot outside the team was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "x.csv:4: robot 'd' is not in the team (a, b, c)");
  }
}

TEST(RadioTrace, ARecordedRunReplaysToTheSameTransfers) {
  for (const comm::RadioParams& model : {comm::RadioParams::wifi(), comm::RadioParams::proRadio()})
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      comm::RadioSimulator original(model, {'a', 'b', 'c'}, seed);
      original.recordLinks(true);
      run(original, 90.0, crossing);
      ASSERT_GT(original.stats().delivered, 5u);
      std::ostringstream text;
      comm::RadioTrace::fromRecords(original.linkRecords(), model.step).write(text);

      comm::RadioParams replay = model;
      replay.trace = std::make_shared<const comm::RadioTrace>(parse(text.str(), "recorded.csv"));
      comm::RadioSimulator again(replay, {'a', 'b', 'c'}, seed);
      run(again, 90.0, crossing);
      EXPECT_EQ(withoutLink(again.transferLog()), withoutLink(original.transferLog())) << "seed " << seed;
      EXPECT_EQ(again.stats().fallback_samples, 0u);  // every sample from the trace
      EXPECT_EQ(again.stats().trace_samples, original.linkRecords().size());
      for (const comm::Transfer& x : again.transferLog()) EXPECT_EQ(x.link, comm::Transfer::Link::Trace);
      EXPECT_LT(replay.trace->windowCount(), original.linkRecords().size());  // steps merged into windows
    }
}

TEST(RadioTrace, NoDeliveriesInABlackoutAndTheDistanceModelAfterTheTrace) {
  comm::RadioParams p = comm::RadioParams::wifi();
  p.trace = std::make_shared<const comm::RadioTrace>(comm::RadioTrace::read(kBlackout));
  comm::RadioSimulator sim(p, {'a', 'b', 'c'}, 5);
  run(sim, 75.0, [](char r, double) { return Eigen::Vector3d(5.0 * (r - 'a'), 0.0, 0.0); });
  std::size_t before = 0, after = 0, late = 0;
  for (const comm::Transfer& x : sim.transferLog()) {
    if (x.outcome != comm::Transfer::Outcome::Delivered) continue;
    const double mid = x.received - 0.5 * p.step;  // the step's interval (received - 0.1, received]
    EXPECT_FALSE(mid >= 20.0 && mid < 30.0) << x.sender << "->" << x.receiver << " received at " << x.received;
    EXPECT_FALSE(x.end - 0.5 * p.step >= 20.0 && x.end - 0.5 * p.step < 30.0);  // no last byte sent in it
    before += mid < 20.0;
    after += mid >= 30.0 && mid < 60.0;
    late += mid >= 60.0;
  }
  EXPECT_GT(before, 10u);
  EXPECT_GT(after, 10u);
  EXPECT_GT(late, 0u);  // phi(d) at 5-10 m carries on after the trace
  EXPECT_GT(sim.stats().trace_samples, 0u);
  EXPECT_GT(sim.stats().fallback_samples, 0u);
  const auto summary = transferSummary(sim);
  EXPECT_EQ(summary["trace"]["windows"], 9u);
  EXPECT_EQ(summary["trace"]["samples_from_distance_model"], sim.stats().fallback_samples);
}

TEST(RadioTrace, LatencyDelaysTheReceiverNotTheLink) {
  comm::RadioParams p = comm::RadioParams::wifi();
  p.trace = std::make_shared<const comm::RadioTrace>(
      parse("robot_a,robot_b,start,duration,throughput_Bps,latency,connected\na,b,0,100,1000000,0.35,1\n"));
  comm::RadioSimulator sim(p, {'a', 'b'}, 2);
  run(sim, 40.0, [](char r, double) { return Eigen::Vector3d(r == 'a' ? 0.0 : 500.0, 0.0, 0.0); });  // beyond d_init
  std::size_t delivered = 0;
  double last_end = -1.0;
  for (const comm::Transfer& x : sim.transferLog()) {
    ASSERT_EQ(x.outcome, comm::Transfer::Outcome::Delivered);
    EXPECT_NEAR(x.received, x.end + 0.4, 1e-9);  // the first step at or after end + 0.35
    EXPECT_GE(x.end, last_end);
    last_end = x.end;
    ++delivered;
  }
  EXPECT_GE(delivered, 30u);
  // The link is free once the last byte is sent: a next transfer of the pair starts before the previous arrives.
  bool overlapping = false;
  for (std::size_t i = 1; i < sim.transferLog().size(); ++i)
    overlapping |= sim.transferLog()[i].start < sim.transferLog()[i - 1].received;
  EXPECT_TRUE(overlapping);
}
