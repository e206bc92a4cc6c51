// The radio's state as shown while it runs (comm/radio_status.hpp): counters, active transfers, what waits per
// link, and a link's mean throughput.
#include <gtest/gtest.h>

#include "cosmo/comm/radio_status.hpp"

using namespace cosmo;

TEST(RadioStatus, CountsActiveTransfersAndWhatWaitsPerLink) {
  comm::RadioParams p = comm::RadioParams::wifi();
  p.timeout = 1e9;
  comm::RadioSimulator sim(p, {'a', 'b'}, 7);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {1, 0, 0}, true);
  sim.offerKeyframe('a', 0, 1000000000000ULL);
  sim.offerKeyframe('a', 1, 1000000000000ULL);
  for (int i = 0; i < 1000 && sim.activeCommunications().empty(); ++i) sim.step(sim.nextStepTime());
  ASSERT_FALSE(sim.activeCommunications().empty());
  const nlohmann::json j = radioStatus(sim, 12.5);
  EXPECT_EQ(j["time"], 12.5);
  ASSERT_EQ(j["active"].size(), 1u);
  EXPECT_EQ(j["active"][0]["sender"], "a");
  EXPECT_EQ(j["active"][0]["receiver"], "b");
  EXPECT_EQ(j["pending"]["a->b"], sim.undeliveredCount('a', 'b'));
  EXPECT_EQ(j["pending"]["b->a"], 0u);
  EXPECT_EQ(j["steps"], sim.stats().steps);
}

TEST(RadioStatus, LinkThroughputIsTheMeanRateSinceTheStartOverTheBandwidth) {
  comm::RadioParams p = comm::RadioParams::wifi();
  comm::ActiveCommunication c;
  c.start = 10.0;
  c.bytes_delivered = 0.5 * p.bandwidthBps() * (4.0 + p.step);  // half the bandwidth over 4 s + one step
  EXPECT_NEAR(linkThroughputFraction(c, 14.0, p), 0.5, 1e-12);
  c.bytes_delivered = 0.0;
  EXPECT_EQ(linkThroughputFraction(c, 10.0, p), 0.0);
}
