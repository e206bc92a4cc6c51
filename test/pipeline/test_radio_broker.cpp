// The comm_broker's radio without ROS (pipeline/radio_broker.hpp): lockstep requests run once the radio is started
// from the sequence and the offers they name arrived, with the grid, seed and robot states of the offline rule
// (advanceRadio); real-time steps follow the time given; payloads reach the receiver as the PayloadStore keeps them.
#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <vector>

#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/scan_compression.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/pipeline/radio_broker.hpp"
#include "cosmo/sequence/seed_streams.hpp"
#include "cosmo/pipeline/team_radio.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;
using namespace cosmo::sequence;

namespace {

constexpr StampNs kStart = 1700000000123456789ULL;  // sequence start, off the 0.1 s grid

std::shared_ptr<const Scan> scanOf(int points, StampNs stamp) {
  auto scan = std::make_shared<Scan>();
  scan->stamp = stamp;
  for (int i = 0; i < points; ++i) {
    scan->points.emplace_back(0.5f * static_cast<float>(i), -0.25f * static_cast<float>(i), 1.0f);
  }
  return scan;
}

/// Robot `robot` standing still at `x` for the whole sequence.
Trajectory standing(double x) {
  Trajectory t;
  Pose3 p = Pose3::Identity();
  p.translation() = Eigen::Vector3d(x, 0, 0);
  t.append(kStart, p);
  t.append(kStart + 100000000000ULL, p);
  return t;
}

QueuedRadioStep request(std::uint32_t seq, StampNs through, bool on, std::uint32_t a_keyframes) {
  QueuedRadioStep q;
  q.seq = seq;
  q.order.through = through;
  q.order.robots = {'a', 'b'};
  q.order.on = {on, on};
  q.order.keyframes = {a_keyframes, 0};
  return q;
}

struct Recorded {
  std::vector<RadioBroker::StepDone> done;
  std::vector<std::pair<StampNs, comm::Transfer>> delivered;
  std::vector<std::shared_ptr<const Scan>> scans;
  RadioBroker::DeliveryFn onDelivery() {
    return [this](const RadioBroker::Delivery& d) {
      if (!d.delivered() || !d.scan) return false;
      delivered.emplace_back(d.step_stamp, d.transfer);
      scans.push_back(d.scan);
      return true;
    };
  }
  RadioBroker::StepDoneFn onDone() {
    return [this](const RadioBroker::StepDone& d) { done.push_back(d); };
  }
};

RadioBroker lockstepBroker(bool compress) {
  RadioBroker broker(comm::RadioParams::wifi(), {'a', 'b'}, 99, true, compress, 6);
  return broker;
}

/// A lockstep broker started on sequence seed 3, robot a standing at x = 0 and b at x = `b_x`.
RadioBroker startedBroker(bool compress, double b_x) {
  RadioBroker broker = lockstepBroker(compress);
  broker.setSequence(kStart, 3, {'a', 'b'});
  broker.setReference('a', standing(0.0));
  broker.setReference('b', standing(b_x));
  broker.start();
  return broker;
}

}  // namespace

TEST(RadioBroker, LockstepRequestsWaitForTheSequenceTheReferencesAndTheOffers) {
  RadioBroker broker(comm::RadioParams::wifi(), {'a', 'b'}, 99, true, false, 6);
  Recorded rec;
  broker.request(request(1, kStart + 1000000000ULL, true, 1));
  broker.runReadySteps(rec.onDelivery(), rec.onDone());
  EXPECT_TRUE(rec.done.empty());  // not started

  EXPECT_TRUE(broker.setSequence(kStart, 42, {'a', 'b'}).empty());
  EXPECT_FALSE(broker.readyToStart());  // b's reference is missing
  broker.setReference('a', standing(0.0));
  broker.setReference('b', standing(5.0));
  ASSERT_TRUE(broker.readyToStart());
  EXPECT_EQ(broker.start(), deriveSeed(42, "radio"));
  EXPECT_EQ(broker.origin(), radioGridOrigin(kStart, comm::RadioParams::wifi().step));
  EXPECT_FALSE(broker.readyToStart());

  broker.runReadySteps(rec.onDelivery(), rec.onDone());
  EXPECT_TRUE(rec.done.empty());  // a's keyframe offer is on its way
  broker.offer('a', 0, broker.pack(scanOf(50, kStart + 10)));
  broker.runReadySteps(rec.onDelivery(), rec.onDone());
  ASSERT_EQ(rec.done.size(), 1u);
  const RadioBroker::StepDone& done = rec.done.front();
  EXPECT_EQ(done.seq, 1u);
  EXPECT_EQ(done.steps, 11u);  // radio times 0 .. 1.0 s: through 1 s after a start 0.023 s past the grid
  EXPECT_EQ(done.last_step, broker.origin() + 1000000000ULL);
  EXPECT_EQ(done.next_step, broker.origin() + 1100000000ULL - 10);
  ASSERT_EQ(rec.delivered.size(), 1u);  // 600 bytes at 5 m: through in a step
  EXPECT_EQ(rec.delivered[0].second.sender, 'a');
  EXPECT_EQ(rec.delivered[0].second.receiver, 'b');
  EXPECT_EQ(rec.delivered[0].first, radioStepStamp(broker.origin(), rec.delivered[0].second.end));
  EXPECT_EQ(done.delivered.at('b'), 1u);
  EXPECT_EQ(done.delivered.at('a'), 0u);
  EXPECT_EQ(rec.scans[0]->points.size(), 50u);
}

TEST(RadioBroker, LockstepRunsTheOfflineRuleWithTheSequenceSeed) {
  // The same offers, states and steps through advanceRadio on a radio seeded as TeamRun seeds it: the same transfers.
  RadioBroker broker = lockstepBroker(false);
  broker.offer('a', 0, broker.pack(scanOf(4000, kStart)));  // before the start: offered again once re-seeded
  broker.offer('b', 0, broker.pack(scanOf(3000, kStart)));
  broker.setSequence(kStart, 7, {'a', 'b'});
  broker.setReference('a', standing(0.0));
  broker.setReference('b', standing(20.0));
  broker.start();
  Recorded rec;
  broker.request(request(1, kStart + 30000000000ULL, true, 1));
  broker.runReadySteps(rec.onDelivery(), rec.onDone());

  comm::RadioSimulator offline(comm::RadioParams::wifi(), {'a', 'b'}, deriveSeed(7, "radio"));
  offline.offerKeyframe('a', 0, comm::rawPayloadBytes(*scanOf(4000, kStart)),
                        comm::rawPayloadBytes(*scanOf(4000, kStart)));
  offline.offerKeyframe('b', 0, comm::rawPayloadBytes(*scanOf(3000, kStart)),
                        comm::rawPayloadBytes(*scanOf(3000, kStart)));
  const StampNs origin = radioGridOrigin(kStart, comm::RadioParams::wifi().step);
  std::vector<std::pair<StampNs, comm::Transfer>> expected;
  advanceRadio(
      offline, origin, kStart + 30000000000ULL,
      [](char r, StampNs) {
        RadioRobotState s;
        s.on = true;
        s.position = Eigen::Vector3d(r == 'a' ? 0.0 : 20.0, 0, 0);
        return s;
      },
      [&](StampNs stamp, const comm::Transfer& t) {
        if (t.outcome == comm::Transfer::Outcome::Delivered) expected.emplace_back(stamp, t);
      });
  ASSERT_EQ(rec.delivered.size(), 2u);  // both ways
  ASSERT_EQ(rec.delivered.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(rec.delivered[i].first, expected[i].first);
    EXPECT_EQ(rec.delivered[i].second.sender, expected[i].second.sender);
    EXPECT_EQ(rec.delivered[i].second.keyframe, expected[i].second.keyframe);
    EXPECT_EQ(rec.delivered[i].second.bytes, expected[i].second.bytes);
  }
}

TEST(RadioBroker, RobotsOffOrWithoutAReferenceAtTheirReportedPosition) {
  RadioBroker broker = lockstepBroker(false);
  broker.offer('a', 0, broker.pack(scanOf(50, kStart)));
  const std::vector<char> missing = broker.setSequence(kStart, 1, {'a'});
  ASSERT_EQ(missing, std::vector<char>{'b'});
  broker.setReference('a', standing(0.0));
  ASSERT_TRUE(broker.readyToStart());                        // b: no reference, positions as reported
  broker.positionReported('b', Eigen::Vector3d(500, 0, 0));  // far out of range
  broker.start();
  Recorded rec;
  broker.request(request(1, kStart + 5000000000ULL, false, 1));  // both off
  broker.request(request(2, kStart + 10000000000ULL, true, 1));  // on, but b far away
  broker.runReadySteps(rec.onDelivery(), rec.onDone());
  ASSERT_EQ(rec.done.size(), 2u);
  EXPECT_TRUE(rec.delivered.empty());
  EXPECT_EQ(rec.done[1].seq, 2u);
  broker.positionReported('b', Eigen::Vector3d(3, 0, 0));
  broker.request(request(3, kStart + 15000000000ULL, true, 1));
  broker.runReadySteps(rec.onDelivery(), rec.onDone());
  ASSERT_EQ(rec.delivered.size(), 1u);
  EXPECT_EQ(rec.done.back().delivered.at('b'), 1u);
}

TEST(RadioBroker, CompressedPayloadsArriveDecompressedWithTheKeyframeStamp) {
  RadioBroker broker = startedBroker(true, 2.0);
  const auto sent = scanOf(200, kStart + 777);
  broker.offer('a', 4, broker.pack(sent));
  Recorded rec;
  broker.request(request(1, kStart + 5000000000ULL, true, 1));
  broker.runReadySteps(rec.onDelivery(), rec.onDone());
  ASSERT_EQ(rec.scans.size(), 1u);
  EXPECT_NE(rec.scans[0], sent);  // a decompressed copy ...
  EXPECT_EQ(rec.scans[0]->stamp, sent->stamp);
  ASSERT_EQ(rec.scans[0]->points.size(), sent->points.size());
  for (std::size_t i = 0; i < sent->points.size(); ++i) {  // ... with the same x y z
    EXPECT_EQ(rec.scans[0]->points[i].x(), sent->points[i].x());
    EXPECT_EQ(rec.scans[0]->points[i].y(), sent->points[i].y());
    EXPECT_EQ(rec.scans[0]->points[i].z(), sent->points[i].z());
  }
  EXPECT_EQ(rec.delivered[0].second.keyframe, 4u);
}

TEST(RadioBroker, AHandOverTheCallerRefusesIsNotCounted) {
  RadioBroker broker = startedBroker(false, 2.0);
  broker.offer('a', 0, broker.pack(scanOf(50, kStart)));
  std::size_t seen = 0;
  std::vector<RadioBroker::StepDone> done;
  broker.request(request(1, kStart + 5000000000ULL, true, 1));
  broker.runReadySteps(
      [&](const RadioBroker::Delivery& d) {
        seen += d.delivered();
        return false;
      },
      [&](const RadioBroker::StepDone& d) { done.push_back(d); });
  EXPECT_EQ(seen, 1u);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].delivered.at('b'), 0u);
}

TEST(RadioBroker, RealTimeStepsFollowTheTimeGivenAndRestartAfterAJump) {
  RadioBroker broker(comm::RadioParams::wifi(), {'a', 'b'}, 5, false, false, 6);
  EXPECT_FALSE(broker.positionReported('a', Eigen::Vector3d(NAN, 0, 0)));
  EXPECT_TRUE(broker.positionReported('a', Eigen::Vector3d(0, 0, 0)));
  EXPECT_TRUE(broker.positionReported('b', Eigen::Vector3d(4, 0, 0)));
  broker.offer('a', 0, broker.pack(scanOf(50, 0)));
  Recorded rec;
  RadioBroker::StepBatch batch = broker.stepRealTime(100.05, rec.onDelivery());
  EXPECT_FALSE(batch.grid_restarted);
  EXPECT_EQ(batch.steps, 0u);  // the grid starts at 100.1
  batch = broker.stepRealTime(100.35, rec.onDelivery());
  EXPECT_EQ(batch.steps, 3u);  // 100.1, 100.2, 100.3
  EXPECT_NEAR(batch.last_time, 100.3, 1e-9);
  EXPECT_EQ(rec.delivered.size(), 1u);
  EXPECT_EQ(broker.delivered().at('b'), 1u);
  EXPECT_FALSE(batch.links.empty());
  batch = broker.stepRealTime(50.0, rec.onDelivery());
  EXPECT_TRUE(batch.time_went_back);
  EXPECT_EQ(batch.steps, 0u);
  batch = broker.stepRealTime(9000.0, rec.onDelivery());
  EXPECT_TRUE(batch.grid_restarted);
  EXPECT_EQ(batch.steps, 1u);  // the new grid's first step, at 9000
  EXPECT_NEAR(batch.last_time, 9000.0, 1e-9);
}

TEST(RadioBroker, LockstepReplaysARadioTraceWithTheOfflineRuleAndLog) {
  // A trace with latency, a blackout, and a pair left to phi(d): the broker's transfer log is the offline rule's.
  comm::RadioParams params = comm::RadioParams::wifi();
  std::istringstream text(
      "robot_a,robot_b,start,duration,throughput_Bps,latency,connected\n"
      "a,b,0,8,300000,0.25,1\na,b,8,4,300000,0,0\na,b,12,20,800000,0.05,1\n");
  params.trace = std::make_shared<const comm::RadioTrace>(comm::RadioTrace::parse(text, "trace.csv"));
  RadioBroker broker(params, {'a', 'b', 'c'}, 99, true, false, 6);
  std::vector<std::shared_ptr<const Scan>> scans;
  for (int k = 0; k < 12; ++k) scans.push_back(scanOf(20000 + 1000 * k, kStart + k));
  for (int k = 0; k < 12; ++k) broker.offer(k % 2 ? 'a' : 'b', static_cast<std::uint32_t>(k), broker.pack(scans[k]));
  broker.setSequence(kStart, 7, {'a', 'b', 'c'});
  broker.setReference('a', standing(0.0));
  broker.setReference('b', standing(200.0));  // beyond d_init: only the trace connects a and b
  broker.setReference('c', standing(10.0));   // a-c: phi(d)
  broker.start();
  Recorded rec;
  QueuedRadioStep q;
  q.seq = 1;
  q.order.through = kStart + 40000000000ULL;
  q.order.robots = {'a', 'b', 'c'};
  q.order.on = {true, true, true};
  q.order.keyframes = {6, 6, 0};
  broker.request(q);
  broker.runReadySteps(rec.onDelivery(), rec.onDone());

  comm::RadioSimulator offline(params, {'a', 'b', 'c'}, deriveSeed(7, "radio"));
  for (int k = 0; k < 12; ++k)
    offline.offerKeyframe(k % 2 ? 'a' : 'b', k, comm::rawPayloadBytes(*scans[k]), comm::rawPayloadBytes(*scans[k]));
  advanceRadio(
      offline, radioGridOrigin(kStart, params.step), q.order.through,
      [](char r, StampNs) {
        RadioRobotState s;
        s.on = true;
        s.position = Eigen::Vector3d(r == 'a' ? 0.0 : r == 'b' ? 200.0 : 10.0, 0, 0);
        return s;
      },
      [](StampNs, const comm::Transfer&) {});
  std::ostringstream got, want;
  writeTransferCsv(got, broker.radio().transferLog());
  writeTransferCsv(want, offline.transferLog());
  EXPECT_EQ(got.str(), want.str());
  std::size_t ab = 0;
  for (const comm::Transfer& x : broker.radio().transferLog()) {
    if (x.outcome != comm::Transfer::Outcome::Delivered || x.sender == 'c' || x.receiver == 'c') continue;
    ++ab;
    EXPECT_FALSE(x.end - 0.05 >= 8.0 && x.end - 0.05 < 12.0) << "sent in the blackout, at " << x.end;
    EXPECT_GT(x.received, x.end);  // latency
  }
  EXPECT_GT(ab, 4u);
  EXPECT_GT(broker.radio().stats().fallback_samples, 0u);  // a-c and b-c
  EXPECT_EQ(rec.delivered.size(), broker.radio().stats().delivered);
  for (const auto& [stamp, x] : rec.delivered) EXPECT_EQ(stamp, radioStepStamp(broker.origin(), x.received));
}
