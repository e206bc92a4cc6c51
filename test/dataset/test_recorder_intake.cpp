// The recorder's intake (dataset/recorder_intake.hpp): duplicates dropped, acknowledgements as the contiguous prefix
// of sequence numbers held, what a restarted front-end continues from, and a restart settling what was lost.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cosmo/dataset/recorder_intake.hpp"
#include "cosmo/jrl/dataset.hpp"

using namespace cosmo;
using namespace cosmo::dataset;

namespace {

MeasurementRecord keyframe(char robot, std::uint64_t seq, std::uint32_t index, std::uint32_t skipped = 0) {
  KeyframeMeasurement k;
  k.robot = robot;
  k.index = index;
  k.stamp = 1000 + index;
  k.scans_skipped = skipped;
  return MeasurementRecord{robot, seq, k};
}

MeasurementRecord closure(char owner, std::uint64_t seq, jrl::Key key1, jrl::Key key2) {
  LoopClosureMeasurement lc;
  lc.owner = owner;
  lc.key1 = key1;
  lc.key2 = key2;
  return MeasurementRecord{owner, seq, lc};
}

}  // namespace

TEST(RecorderIntake, DropsDuplicatesAndAcknowledgesTheContiguousPrefix) {
  RecorderIntake in({'a', 'b'});
  EXPECT_EQ(in.acked('a'), 0u);
  EXPECT_TRUE(in.take(keyframe('a', 1, 0)));
  EXPECT_TRUE(in.take(keyframe('a', 3, 2)));
  EXPECT_EQ(in.acked('a'), 1u) << "2 is missing";
  EXPECT_EQ(in.highest('a'), 3u);
  EXPECT_FALSE(in.take(keyframe('a', 3, 2))) << "a duplicate";
  EXPECT_FALSE(in.take(keyframe('a', 1, 0)));
  EXPECT_TRUE(in.take(closure('a', 2, jrl::symbol('a', 1), jrl::symbol('b', 4))));
  EXPECT_EQ(in.acked('a'), 3u);
  EXPECT_EQ(in.keyframes('a'), 2u);
  EXPECT_EQ(in.loopClosures('a'), 1u);
  EXPECT_TRUE(in.holds('a', 2));
  EXPECT_FALSE(in.holds('a', 4));
  EXPECT_EQ(in.acked('b'), 0u) << "numbers are per sending robot";
  EXPECT_TRUE(in.take(keyframe('b', 1, 0)));
}

TEST(RecorderIntake, AnyArrivalOrderEndsTheSame) {
  std::vector<MeasurementRecord> records;
  for (std::uint32_t i = 0; i < 50; ++i) records.push_back(keyframe('a', i + 1, i));
  std::mt19937_64 rng(5);
  for (int round = 0; round < 5; ++round) {
    std::shuffle(records.begin(), records.end(), rng);
    RecorderIntake in({'a'});
    std::size_t taken = 0;
    for (const auto& r : records) taken += in.take(r) ? 1 : 0;
    for (const auto& r : records) EXPECT_FALSE(in.take(r));
    EXPECT_EQ(taken, 50u);
    EXPECT_EQ(in.acked('a'), 50u);
  }
}

TEST(RecorderIntake, NextIndexCoversEveryKeySeen) {
  RecorderIntake in({'a', 'b'});
  in.take(keyframe('a', 1, 0));
  in.take(keyframe('a', 2, 1, 4));
  EXPECT_EQ(in.nextIndex('a'), 2u);
  EXPECT_EQ(in.scansSkipped('a'), 4u);
  // b's closure names a5, a keyframe the recorder never got (it reached b through the radio)
  in.take(closure('b', 1, jrl::symbol('b', 0), jrl::symbol('a', 5)));
  EXPECT_EQ(in.nextIndex('a'), 6u);
  EXPECT_EQ(in.nextIndex('b'), 1u);
}

TEST(RecorderIntake, ARestartSettlesWhatTheDeadProcessNeverDelivered) {
  RecorderIntake in({'a'});
  in.take(keyframe('a', 1, 0));
  in.take(keyframe('a', 2, 1));
  in.take(keyframe('a', 5, 4));  // 3 and 4 were lost with the process
  EXPECT_EQ(in.acked('a'), 2u);
  MeasurementRecord bridged = keyframe('a', 6, 5);
  std::get<KeyframeMeasurement>(bridged.what).bridge_from = 4;
  EXPECT_TRUE(in.take(bridged));
  EXPECT_EQ(in.acked('a'), 6u);
  EXPECT_EQ(in.restarts('a'), 1u);
  EXPECT_FALSE(in.take(keyframe('a', 3, 2))) << "settled: a late message of the dead process is not taken";
  EXPECT_TRUE(in.take(keyframe('a', 7, 6)));
  EXPECT_EQ(in.acked('a'), 7u);
}

TEST(RecorderIntake, RefusesUnknownRobotsAndSeqZero) {
  RecorderIntake in({'a'});
  EXPECT_THROW(in.take(keyframe('z', 1, 0)), std::invalid_argument);
  EXPECT_THROW(in.take(keyframe('a', 0, 0)), std::invalid_argument);
  EXPECT_THROW(in.acked('z'), std::invalid_argument);
}
