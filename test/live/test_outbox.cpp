// A front-end's outbox (live/outbox.hpp): numbers from 1 (or where a restart continues), kept until
// acknowledged, everything sent again to a new recorder session, a message sent again when not acknowledged
// within resend_after, memory bounded by what is not acknowledged.
#include <gtest/gtest.h>

#include <string>

#include "cosmo/live/outbox.hpp"

using cosmo::live::Outbox;

namespace {
std::vector<std::uint64_t> seqs(const std::vector<std::pair<std::uint64_t, const std::string*>>& due) {
  std::vector<std::uint64_t> out;
  for (const auto& [s, m] : due) out.push_back(s);
  return out;
}
}  // namespace

TEST(Outbox, NumbersAndKeepsUntilAcknowledged) {
  Outbox<std::string> box(1.0);
  EXPECT_EQ(box.lastSeq(), 0u);
  EXPECT_EQ(box.add("k0", 0.0), 1u);
  EXPECT_EQ(box.add("k1", 0.1), 2u);
  EXPECT_EQ(box.add("lc", 0.2), 3u);
  EXPECT_EQ(box.lastSeq(), 3u);
  box.acknowledged("s1", 0);  // the first session heard: nothing was lost, but everything goes again
  EXPECT_EQ(seqs(box.due(0.3)), (std::vector<std::uint64_t>{1, 2, 3}));
  box.acknowledged("s1", 2);
  EXPECT_EQ(box.size(), 1u);
  EXPECT_TRUE(box.due(0.5).empty()) << "sent again 0.2 s ago";
  box.acknowledged("s1", 3);
  EXPECT_EQ(box.size(), 0u);
  EXPECT_TRUE(box.due(10.0).empty());
}

TEST(Outbox, SendsAgainWhatIsNotAcknowledgedWithinResendAfter) {
  Outbox<std::string> box(1.0);
  box.acknowledged("s1", 0);
  box.add("a", 10.0);
  box.add("b", 10.6);
  EXPECT_TRUE(box.due(10.9).empty());
  EXPECT_EQ(seqs(box.due(11.0)), (std::vector<std::uint64_t>{1}));
  EXPECT_EQ(seqs(box.due(11.6)), (std::vector<std::uint64_t>{2}));
  EXPECT_TRUE(box.due(11.7).empty());
  const auto again = box.due(12.0);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(*again[0].second, "a");
}

TEST(Outbox, ANewRecorderSessionGetsEverythingNotAcknowledged) {
  Outbox<std::string> box(1.0);
  box.acknowledged("s1", 0);
  for (int i = 0; i < 5; ++i) box.add("m" + std::to_string(i), 0.0);
  box.acknowledged("s1", 2);
  box.acknowledged("s2", 2);  // a respawned recorder, resumed from its journal
  EXPECT_EQ(seqs(box.due(0.1)), (std::vector<std::uint64_t>{3, 4, 5}));
  EXPECT_TRUE(box.due(0.2).empty());
}

TEST(Outbox, ARestartedFrontendNumbersFromWhereItsRobotLeftOff) {
  Outbox<int> box;
  box.numberFrom(42);
  EXPECT_EQ(box.add(7, 0.0), 42u);
  EXPECT_EQ(box.lastSeq(), 42u);
}

TEST(Outbox, MemoryIsWhatIsNotAcknowledged) {
  Outbox<std::string> box(1.0);
  for (int i = 0; i < 1000; ++i) {
    box.add(std::string(100, 'x'), i * 0.1);
    box.acknowledged("s", box.lastSeq() > 3 ? box.lastSeq() - 3 : 0);
  }
  EXPECT_EQ(box.size(), 3u);
}
