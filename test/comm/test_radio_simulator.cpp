// Statistical and behavioural tests of the radio model (paper Algorithm 1).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "cosmo/comm/radio_simulator.hpp"

using namespace cosmo;

namespace {

constexpr std::size_t kHuge = 1000000000000ULL;  // a payload that never completes

/// Runs steps on the grid until `cond` holds or `max_steps` pass; returns the transfers that ended.
template <typename Cond>
std::vector<comm::Transfer> stepUntil(comm::RadioSimulator& sim, Cond cond, int max_steps = 100000) {
  std::vector<comm::Transfer> all;
  for (int i = 0; i < max_steps && !cond(); ++i) {
    const auto ended = sim.step(sim.nextStepTime());
    all.insert(all.end(), ended.begin(), ended.end());
  }
  return all;
}

comm::RadioParams realSizes(comm::RadioParams p) {
  p.size_model = comm::RadioParams::SizeModel::RealCompressed;
  return p;
}

/// A pair a-b at distance d with one endless transfer a -> b started at close range.
comm::RadioSimulator endlessPair(const comm::RadioParams& p, std::uint64_t seed) {
  comm::RadioParams q = realSizes(p);
  q.timeout = 1e9;
  comm::RadioSimulator sim(q, {'a', 'b'}, seed);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {1, 0, 0}, true);
  sim.offerKeyframe('a', 0, kHuge);
  stepUntil(sim, [&] { return !sim.activeCommunications().empty(); });
  EXPECT_EQ(sim.activeCommunications().size(), 1u);
  return sim;
}

comm::RadioParams certainLink() {  // phi = 1 for d < ~0.9 r_max
  comm::RadioParams p = realSizes(comm::RadioParams::wifi());
  p.p_max = 1.0;
  p.alpha = 100.0;
  return p;
}

}  // namespace

// The observed connectivity frequency of an active link at distance d matches phi(d) within sampling error.
TEST(RadioSimulator, ConnectivityFrequencyMatchesPhi) {
  const int n = 4000;
  for (const comm::RadioParams& p : {comm::RadioParams::wifi(), comm::RadioParams::proRadio()}) {
    for (double frac : {0.02, 0.15, 0.3, 0.5, 0.7, 0.9, 1.2}) {
      const double d = frac * p.r_max;
      comm::RadioSimulator sim = endlessPair(p, 11 + static_cast<std::uint64_t>(1000 * frac));
      sim.setRobotState('b', {d, 0, 0}, true);
      const auto before = sim.stats();
      stepUntil(
          sim, [] { return false; }, n);
      const double samples = sim.stats().link_samples - before.link_samples;
      const double freq = (sim.stats().link_successes - before.link_successes) / samples;
      const double phi = p.phi(d);
      const double sigma = std::sqrt(std::max(phi * (1 - phi), 1e-6) / samples);
      EXPECT_EQ(samples, n);
      EXPECT_NEAR(freq, phi, 4.5 * sigma + 1e-9) << "B=" << p.bandwidth_kBps << " d=" << d;
    }
  }
}

// A clean link (one pair, nobody else around) carries B * P_max on average.
TEST(RadioSimulator, CleanLinkThroughputIsBandwidthTimesPmax) {
  for (const comm::RadioParams& p : {comm::RadioParams::wifi(), comm::RadioParams::proRadio()}) {
    comm::RadioSimulator sim = endlessPair(p, 5);
    const int n = 5000;
    const double before = sim.activeCommunications().front().bytes_delivered;
    stepUntil(
        sim, [] { return false; }, n);
    const double rate = (sim.activeCommunications().front().bytes_delivered - before) / (n * p.step);
    const double expected = p.bandwidthBps() * p.p_max;
    const double sigma = p.bandwidthBps() * std::sqrt(p.p_max * (1 - p.p_max) / n);
    EXPECT_NEAR(rate, expected, 4.5 * sigma) << "B=" << p.bandwidth_kBps;
    EXPECT_EQ(sim.activeCommunications().front().interference, 1);
  }
}

// Two overlapping communications each get B / 2; apart (beyond d_intf) each gets B.
TEST(RadioSimulator, OverlappingCommunicationsShareBandwidth) {
  const comm::RadioParams p = certainLink();
  for (double separation : {10.0, 1000.0}) {
    comm::RadioSimulator sim(p, {'a', 'b', 'c', 'd'}, 3);
    sim.setRobotState('a', {0, 0, 0}, true);
    sim.setRobotState('b', {1, 0, 0}, true);
    sim.setRobotState('c', {separation, 0, 0}, true);
    sim.setRobotState('d', {separation + 1, 0, 0}, true);
    for (char r : {'a', 'b', 'c', 'd'}) sim.offerKeyframe(r, 0, kHuge);
    sim.step(sim.nextStepTime());
    ASSERT_EQ(sim.activeCommunications().size(), 2u);
    const int expected_i = separation < p.d_intf ? 2 : 1;
    for (const auto& c : sim.activeCommunications()) {
      EXPECT_EQ(c.interference, expected_i);
      EXPECT_DOUBLE_EQ(c.throughput_Bps, p.bandwidthBps() / expected_i);
      EXPECT_DOUBLE_EQ(c.bytes_delivered, p.bandwidthBps() / expected_i * p.step);
    }
  }
  // Statistically with the Wi-Fi model: mean throughput of each of two overlapping links = B P_max / 2.
  comm::RadioParams w = realSizes(comm::RadioParams::wifi());
  w.timeout = 1e9;
  comm::RadioSimulator sim(w, {'a', 'b', 'c', 'd'}, 9);
  const Eigen::Vector3d pos[4] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {2, 3, 0}};
  for (int i = 0; i < 4; ++i) {
    sim.setRobotState(static_cast<char>('a' + i), pos[i], true);
    sim.offerKeyframe(static_cast<char>('a' + i), 0, kHuge);
  }
  stepUntil(sim, [&] { return sim.activeCommunications().size() == 2; });
  ASSERT_EQ(sim.activeCommunications().size(), 2u);
  const int n = 5000;
  std::vector<double> before;
  for (const auto& c : sim.activeCommunications()) before.push_back(c.bytes_delivered);
  stepUntil(
      sim, [] { return false; }, n);
  const double sigma = w.bandwidthBps() / 2 * std::sqrt(w.p_max * (1 - w.p_max) / n);
  for (std::size_t i = 0; i < 2; ++i) {
    const double rate = (sim.activeCommunications()[i].bytes_delivered - before[i]) / (n * w.step);
    EXPECT_NEAR(rate, w.bandwidthBps() * w.p_max / 2, 4.5 * sigma);
  }
}

// Payload completion time follows from the shared bandwidth: 300 kB at 2000 kB/s takes 2 steps alone and 3
// steps when another communication overlaps.
TEST(RadioSimulator, CompletionTimeFollowsBandwidth) {
  const comm::RadioParams p = certainLink();
  comm::RadioSimulator alone(p, {'a', 'b'}, 1);
  alone.setRobotState('a', {0, 0, 0}, true);
  alone.setRobotState('b', {5, 0, 0}, true);
  alone.offerKeyframe('a', 7, 300000);
  std::vector<comm::Transfer> got = stepUntil(alone, [&] { return alone.stats().delivered > 0; });
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].outcome, comm::Transfer::Outcome::Delivered);
  EXPECT_EQ(got[0].keyframe, 7u);
  EXPECT_NEAR(got[0].end - got[0].start, 0.1, 1e-9);  // steps at start and start + 0.1
  EXPECT_TRUE(alone.wasDelivered('a', 'b', 7));
  EXPECT_EQ(alone.undeliveredCount('a', 'b'), 0u);
}

// A pair that moves apart while communicating times out T after its last progress (NoProgress mode), or T
// after its start (TotalDuration mode).
TEST(RadioSimulator, PairMovingApartTimesOut) {
  comm::RadioParams p = realSizes(comm::RadioParams::wifi());
  comm::RadioSimulator sim(p, {'a', 'b'}, 21);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {3, 0, 0}, true);
  sim.offerKeyframe('a', 0, kHuge);
  stepUntil(sim, [&] { return !sim.activeCommunications().empty(); });
  for (int i = 0; i < 5; ++i) sim.step(sim.nextStepTime());
  ASSERT_EQ(sim.activeCommunications().size(), 1u);
  const double last_progress = sim.activeCommunications().front().last_progress;
  const double moved_at = sim.nextStepTime();
  sim.setRobotState('b', {150, 0, 0}, true);  // phi = 0
  const auto ended = stepUntil(
      sim, [&] { return sim.stats().timed_out > 0; }, 1000);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].outcome, comm::Transfer::Outcome::TimedOut);
  EXPECT_NEAR(ended[0].end, last_progress + p.timeout, 1e-6);
  EXPECT_LE(ended[0].end, moved_at + p.timeout);
  EXPECT_LT(ended[0].bytes_delivered, static_cast<double>(ended[0].bytes));
  EXPECT_FALSE(sim.wasDelivered('a', 'b', 0));
  // Far apart nothing starts again.
  stepUntil(
      sim, [] { return false; }, 200);
  EXPECT_EQ(sim.stats().initiated, 1u);

  comm::RadioParams total = certainLink();
  total.timeout_mode = comm::RadioParams::TimeoutMode::TotalDuration;
  comm::RadioSimulator sim2(total, {'a', 'b'}, 21);
  sim2.setRobotState('a', {0, 0, 0}, true);
  sim2.setRobotState('b', {3, 0, 0}, true);
  sim2.offerKeyframe('a', 0, 10000000);  // 5 s of a clean link
  const auto ended2 = stepUntil(
      sim2, [&] { return sim2.stats().timed_out > 0; }, 1000);
  ASSERT_EQ(ended2.size(), 1u);
  EXPECT_NEAR(ended2[0].end - ended2[0].start, total.timeout, 1e-6);
}

// Robots are off until their first state; an off robot neither starts nor carries communications.
TEST(RadioSimulator, OffRobotsDoNotCommunicate) {
  comm::RadioSimulator sim(certainLink(), {'a', 'b', 'c'}, 4);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {1, 0, 0}, false);
  for (char r : {'a', 'b', 'c'}) sim.offerKeyframe(r, 0, 1000);
  stepUntil(
      sim, [] { return false; }, 100);
  EXPECT_EQ(sim.stats().initiated, 0u);
  EXPECT_FALSE(sim.isOn('c'));
  sim.setRobotState('b', {1, 0, 0}, true);  // b comes on; c never does
  stepUntil(
      sim, [] { return false; }, 100);
  EXPECT_TRUE(sim.wasDelivered('a', 'b', 0));
  EXPECT_TRUE(sim.wasDelivered('b', 'a', 0));
  EXPECT_FALSE(sim.wasDelivered('a', 'c', 0));
  EXPECT_EQ(sim.stats().delivered, 2u);
}

// The robot with more undelivered keyframes sends; every keyframe arrives exactly once.
TEST(RadioSimulator, SenderChoiceAndCompleteDelivery) {
  comm::RadioSimulator sim(certainLink(), {'b', 'a'}, 8);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {1, 0, 0}, true);
  for (std::size_t k = 0; k < 5; ++k) sim.offerKeyframe('a', k, 1000 + k);
  sim.offerKeyframe('b', 0, 1000);
  const auto first = sim.step(sim.nextStepTime());
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].sender, 'a');
  stepUntil(
      sim, [] { return false; }, 100);
  std::set<std::pair<char, std::size_t>> seen;
  for (const comm::Transfer& x : sim.transferLog()) {
    EXPECT_EQ(x.outcome, comm::Transfer::Outcome::Delivered);
    EXPECT_TRUE(seen.insert({x.sender, x.keyframe}).second) << "duplicate delivery";
  }
  EXPECT_EQ(seen.size(), 6u);
  EXPECT_EQ(sim.stats().initiated, 6u);  // nothing left to send: no further communication starts
}

// Scan selection is uniform over the undelivered keyframes.
TEST(RadioSimulator, ScanSelectionIsUniform) {
  const int kKeyframes = 4, kSeeds = 800;
  std::vector<int> count(kKeyframes, 0);
  for (int seed = 0; seed < kSeeds; ++seed) {
    comm::RadioSimulator sim(certainLink(), {'a', 'b'}, seed);
    sim.setRobotState('a', {0, 0, 0}, true);
    sim.setRobotState('b', {1, 0, 0}, true);
    for (int k = 0; k < kKeyframes; ++k) sim.offerKeyframe('a', k, 10);
    const auto t = sim.step(0.0);
    ASSERT_EQ(t.size(), 1u);
    ++count[t[0].keyframe];
  }
  double chi2 = 0;
  const double e = static_cast<double>(kSeeds) / kKeyframes;
  for (int c : count) chi2 += (c - e) * (c - e) / e;
  EXPECT_LT(chi2, 16.27);  // chi-square, 3 dof, p = 0.001
}

// The paper's size model: s = f * S with f ~ N(0.653, 0.04), independent of the order of offers.
TEST(RadioSimulator, PaperSizeModel) {
  const comm::RadioParams p = comm::RadioParams::wifi();
  comm::RadioSimulator sim(p, {'a', 'b'}, 77), reversed(p, {'a', 'b'}, 77);
  const std::size_t raw = 65536 * 12;
  const int n = 2000;
  for (int k = 0; k < n; ++k) sim.offerKeyframe('a', k, 0, raw);
  for (int k = n - 1; k >= 0; --k) reversed.offerKeyframe('a', k, 0, raw);
  double sum = 0, sum2 = 0;
  for (int k = 0; k < n; ++k) {
    const double f = static_cast<double>(sim.payloadSize('a', k)) / raw;
    EXPECT_EQ(sim.payloadSize('a', k), reversed.payloadSize('a', k));
    sum += f;
    sum2 += f * f;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.653, 4.5 * 0.04 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.04, 0.004);
  EXPECT_NE(sim.payloadSize('a', 0), sim.payloadSize('a', 1));
}

namespace {
std::vector<comm::Transfer> randomTeamRun(std::uint64_t seed) {
  comm::RadioSimulator sim(comm::RadioParams::wifi(), {'a', 'b', 'c', 'd'}, seed);
  for (int i = 0; i < 3000; ++i) {
    const double t = sim.nextStepTime();
    for (int r = 0; r < 4; ++r) {
      const double ang = 0.01 * i * (r + 1) + r;
      sim.setRobotState(static_cast<char>('a' + r), {30 * std::cos(ang) + 10 * r, 30 * std::sin(ang), 0}, i > 50 * r);
      if (i % 20 == 0) sim.offerKeyframe(static_cast<char>('a' + r), i / 20, 0, 400000);
    }
    sim.step(t);
  }
  return sim.transferLog();
}
bool sameLog(const std::vector<comm::Transfer>& x, const std::vector<comm::Transfer>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i].sender != y[i].sender || x[i].receiver != y[i].receiver || x[i].keyframe != y[i].keyframe ||
        x[i].start != y[i].start || x[i].end != y[i].end || x[i].bytes != y[i].bytes || x[i].outcome != y[i].outcome)
      return false;
  return true;
}
}  // namespace

TEST(RadioSimulator, DeterministicPerSeed) {
  const auto a = randomTeamRun(42), b = randomTeamRun(42), c = randomTeamRun(43);
  EXPECT_GT(a.size(), 20u);
  EXPECT_TRUE(sameLog(a, b));
  EXPECT_FALSE(sameLog(a, c));
  // At most one active communication per robot at any time.
  for (const comm::Transfer& x : a)
    for (const comm::Transfer& y : a) {
      if (&x == &y) continue;
      const bool share =
          x.sender == y.sender || x.sender == y.receiver || x.receiver == y.sender || x.receiver == y.receiver;
      const bool overlap = x.start <= y.end - 1e-9 && y.start <= x.end - 1e-9;
      EXPECT_FALSE(share && overlap) << x.sender << x.receiver << " " << y.sender << y.receiver;
    }
}

TEST(RadioSimulator, BadInput) {
  EXPECT_THROW(comm::RadioSimulator(comm::RadioParams::wifi(), {}, 1), std::invalid_argument);
  comm::RadioParams bad = comm::RadioParams::wifi();
  bad.step = 0;
  EXPECT_THROW(comm::RadioSimulator(bad, {'a'}, 1), std::runtime_error);
  comm::RadioSimulator sim(comm::RadioParams::wifi(), {'a', 'b'}, 1);
  EXPECT_THROW(sim.setRobotState('z', {0, 0, 0}, true), std::invalid_argument);
  EXPECT_THROW(sim.offerKeyframe('z', 0, 10), std::invalid_argument);
  EXPECT_THROW(sim.setRobotState('a', {NAN, 0, 0}, true), std::invalid_argument);
  sim.step(1.0);
  EXPECT_THROW(sim.step(1.0), std::invalid_argument);
  EXPECT_THROW(sim.step(0.5), std::invalid_argument);
  EXPECT_NEAR(sim.nextStepTime(), 1.1, 1e-12);
  sim.step(5.0);  // off the grid: the grid restarts there
  EXPECT_NEAR(sim.nextStepTime(), 5.1, 1e-12);
  // A single robot or a zero-byte payload does not crash.
  comm::RadioSimulator one(comm::RadioParams::wifi(), {'a'}, 1);
  one.setRobotState('a', {0, 0, 0}, true);
  one.offerKeyframe('a', 0, 0);
  EXPECT_TRUE(one.step(0.0).empty());
}
