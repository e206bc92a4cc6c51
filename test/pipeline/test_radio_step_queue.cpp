// The radio's side of the lockstep (pipeline/radio_step_queue.hpp): requests run in order, once the radio is
// started and the keyframe offers they name arrived.
#include <gtest/gtest.h>

#include "cosmo/pipeline/radio_step_queue.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

namespace {
QueuedRadioStep request(std::uint32_t seq, std::uint32_t a_keyframes, std::uint32_t b_keyframes) {
  QueuedRadioStep q;
  q.seq = seq;
  q.order.robots = {'a', 'b'};
  q.order.on = {true, false};
  q.order.keyframes = {a_keyframes, b_keyframes};
  return q;
}
}  // namespace

TEST(RadioStepQueue, NothingRunsBeforeTheRadioIsStarted) {
  RadioStepQueue queue;
  queue.push(request(1, 0, 0));
  EXPECT_FALSE(queue.popReady());
  queue.start();
  const auto ready = queue.popReady();
  ASSERT_TRUE(ready);
  EXPECT_EQ(ready->seq, 1u);
  EXPECT_TRUE(ready->on('a'));
  EXPECT_FALSE(ready->on('b'));
  EXPECT_FALSE(ready->on('c'));  // not named: off
}

TEST(RadioStepQueue, ARequestWaitsForTheOffersItNamesAndKeepsTheOrder) {
  RadioStepQueue queue;
  queue.start();
  queue.push(request(1, 1, 0));
  queue.push(request(2, 0, 0));
  EXPECT_FALSE(queue.popReady());  // a's first offer is on its way; request 2 waits behind it
  queue.offerArrived('b');
  EXPECT_FALSE(queue.popReady());
  queue.offerArrived('a');
  EXPECT_EQ(queue.popReady()->seq, 1u);
  EXPECT_EQ(queue.popReady()->seq, 2u);
  EXPECT_FALSE(queue.popReady());
}
