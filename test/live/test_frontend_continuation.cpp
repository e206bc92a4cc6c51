// Where a front-end's numbering starts (live/frontend_continuation.hpp): afresh, or after everything of its
// robot that the recorder and the comm_broker saw, bridged from the end of the recorded trajectory.
#include <gtest/gtest.h>

#include "cosmo/live/frontend_continuation.hpp"

using namespace cosmo::live;

TEST(FrontendContinuation, AFirstStartStartsAfresh) {
  const Continuation c = continueAfter(RecorderHolding{}, 0);
  EXPECT_FALSE(c.restart);
  EXPECT_EQ(c.first_seq, 1u);
  EXPECT_EQ(c.first_index, 0u);
  EXPECT_FALSE(c.bridge_from);
  EXPECT_NE(c.describe().find("afresh"), std::string::npos);
  EXPECT_FALSE(continueAfter(RecorderHolding{}, std::nullopt).restart);
}

TEST(FrontendContinuation, ARestartContinuesAfterEverythingAnyoneSaw) {
  RecorderHolding r;
  r.highest_seq = 57;
  r.next_index = 21;  // a teammate's closure named keyframe 20
  r.chain_end = 19;
  r.scans_skipped = 9;
  Continuation c = continueAfter(r, 20);
  EXPECT_TRUE(c.restart);
  EXPECT_EQ(c.first_seq, 58u);
  EXPECT_EQ(c.first_index, 21u);
  EXPECT_EQ(c.bridge_from, std::optional<std::uint32_t>(19));
  EXPECT_EQ(c.scans_skipped, 9u);
  // the broker was offered keyframe 22, which nobody recorded
  c = continueAfter(r, 23);
  EXPECT_EQ(c.first_index, 23u);
  EXPECT_NE(c.describe().find("keyframes from 23"), std::string::npos) << c.describe();
}

TEST(FrontendContinuation, OnlyTheBrokerSawTheRobot) {
  const Continuation c = continueAfter(RecorderHolding{}, 3);
  EXPECT_TRUE(c.restart);
  EXPECT_EQ(c.first_index, 3u);
  EXPECT_EQ(c.first_seq, 1u);
  EXPECT_FALSE(c.bridge_from);
}
