// Sequence config loading and the temporal synchronization of spec section 3.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "cosmo_pipeline_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

std::vector<TrialSpan> threeSpans() {
  return {{'a', 1000000000000ULL, 1300000000000ULL},
          {'b', 2000000000000ULL, 2200000000000ULL},
          {'c', 500000000000ULL, 900000000000ULL}};
}

}  // namespace

TEST(SequenceConfig, LoadsAndResolvesRelativePaths) {
  const auto path = writeTemp("seq_ok.yaml", R"(
name: test_r2_00
source: synthetic
seed: 11
anchor: b
trials:
  - robot: a
    name: trial_0
    bag: trial_0.bag
    reference: trial_0_pose_inW.csv
    extrinsic: [1, 2, 3, 0, 0, 0, 1]
  - robot: b
    bag: /abs/trial_1.bag
    topic: /points
)");
  const auto cfg = SequenceConfig::load(path);
  EXPECT_EQ(cfg.name, "test_r2_00");
  EXPECT_EQ(cfg.seed, 11u);
  EXPECT_EQ(cfg.anchor, 'b');
  ASSERT_EQ(cfg.trials.size(), 2u);
  const auto dir = std::filesystem::path(path).parent_path();
  EXPECT_EQ(cfg.trials[0].bag, (dir / "trial_0.bag").string());
  EXPECT_EQ(cfg.trials[0].reference, (dir / "trial_0_pose_inW.csv").string());
  EXPECT_NEAR(cfg.trials[0].extrinsic.translation().y(), 2.0, 1e-12);
  EXPECT_EQ(cfg.trials[1].bag, "/abs/trial_1.bag");
  EXPECT_EQ(cfg.trials[1].topic, "/points");
  EXPECT_TRUE(cfg.trials[1].reference.empty());
  EXPECT_EQ(cfg.trial('b').name, "robot_b");
  EXPECT_EQ(cfg.robots(), (std::vector<char>{'a', 'b'}));
}

TEST(SequenceConfig, ErrorsNameFileAndField) {
  const auto bad_anchor =
      writeTemp("seq_bad_anchor.yaml", "name: x\nanchor: z\ntrials:\n  - robot: a\n    bag: a.bag\n");
  try {
    SequenceConfig::load(bad_anchor);
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("seq_bad_anchor.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("anchor"), std::string::npos) << e.what();
  }
  const auto no_bag = writeTemp("seq_no_bag.yaml", "name: x\ntrials:\n  - robot: a\n");
  try {
    SequenceConfig::load(no_bag);
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("trials[0].bag"), std::string::npos) << e.what();
  }
  const auto dup =
      writeTemp("seq_dup.yaml", "name: x\ntrials:\n  - {robot: a, bag: a.bag}\n  - {robot: a, bag: b.bag}\n");
  EXPECT_THROW(SequenceConfig::load(dup), std::runtime_error);
  EXPECT_THROW(SequenceConfig::load("/nonexistent/seq.yaml"), std::runtime_error);
  const auto bad_extr =
      writeTemp("seq_bad_extr.yaml", "name: x\ntrials:\n  - {robot: a, bag: a.bag, extrinsic: [1, 2]}\n");
  EXPECT_THROW(SequenceConfig::load(bad_extr), std::runtime_error);
}

TEST(SequenceTiming, AnchorStartsAtItsOwnFirstStampOthersShifted) {
  const auto timing = SequenceTiming::synchronize(threeSpans(), 'a', 40.0, 7);
  EXPECT_EQ(timing.of('a').offset_ns, 0);
  EXPECT_EQ(timing.of('a').start(), 1000000000000ULL);
  for (char r : {'b', 'c'}) {
    const double delta = (static_cast<double>(timing.of(r).start()) - 1e12) * 1e-9;
    EXPECT_LT(std::abs(delta), 200.0) << r;  // 5 sigma
    // a whole-trial shift: duration kept
    EXPECT_EQ(timing.of(r).end() - timing.of(r).start(), timing.of(r).last - timing.of(r).first);
    EXPECT_EQ(timing.of(r).toRecorded(timing.of(r).toSequence(timing.of(r).first + 5)), timing.of(r).first + 5);
  }
  EXPECT_LE(timing.start(), timing.of('a').start());
  EXPECT_GE(timing.end(), timing.of('c').end());
}

TEST(SequenceTiming, DeterministicPerSeedAndDifferentAcrossSeeds) {
  const auto t1 = SequenceTiming::synchronize(threeSpans(), 'a', 40.0, 7);
  const auto t2 = SequenceTiming::synchronize(threeSpans(), 'a', 40.0, 7);
  const auto t3 = SequenceTiming::synchronize(threeSpans(), 'a', 40.0, 8);
  EXPECT_EQ(t1.of('b').offset_ns, t2.of('b').offset_ns);
  EXPECT_EQ(t1.of('c').offset_ns, t2.of('c').offset_ns);
  EXPECT_NE(t1.of('b').offset_ns, t3.of('b').offset_ns);
}

TEST(SequenceTiming, OffsetsFollowTheConfiguredSigma) {
  // Many robots' offsets, one draw each: sample std close to sigma.
  std::vector<TrialSpan> spans;
  for (int i = 0; i < 2000; ++i) spans.push_back({static_cast<char>('a' + i % 26), 5000000000000ULL, 5001000000000ULL});
  // robots may repeat here; the timing only needs the anchor to exist
  const auto timing = SequenceTiming::synchronize(spans, 'a', 40.0, 3);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (const auto& t : timing.trials()) {
    if (t.robot == 'a') continue;
    const double d = static_cast<double>(t.start() - 0) * 1e-9 - 5000.0;
    sum += d;
    sum2 += d * d;
    ++n;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0);
  EXPECT_NEAR(sd, 40.0, 3.0);
}

TEST(SequenceTiming, RobotOffBeforeFirstMeasurementOnAfterLast) {
  const auto timing = SequenceTiming::synchronize(threeSpans(), 'a', 40.0, 7);
  const auto& b = timing.of('b');
  EXPECT_FALSE(timing.isOn('b', b.start() - 1));
  EXPECT_TRUE(timing.isOn('b', b.start()));
  EXPECT_TRUE(timing.isOn('b', b.end() + 1000000000ULL));
}

TEST(SequenceTiming, StampsStayPositiveForTrialsStampedFromZero) {
  const std::vector<TrialSpan> spans{{'a', 0, 60000000000ULL}, {'b', 0, 60000000000ULL}, {'c', 0, 60000000000ULL}};
  const auto timing = SequenceTiming::synchronize(spans, 'a', 40.0, 1);
  EXPECT_GE(timing.start(), 1000000000ULL);
  // relative offsets are unchanged by the global shift
  const auto loose = SequenceTiming::synchronize({{'a', 1000000000000ULL, 1060000000000ULL},
                                                  {'b', 1000000000000ULL, 1060000000000ULL},
                                                  {'c', 1000000000000ULL, 1060000000000ULL}},
                                                 'a', 40.0, 1);
  EXPECT_EQ(timing.of('b').offset_ns - timing.of('a').offset_ns, loose.of('b').offset_ns - loose.of('a').offset_ns);
}

TEST(SequenceTiming, BadInputThrows) {
  EXPECT_THROW(SequenceTiming::synchronize({}, 'a', 40.0, 1), std::runtime_error);
  EXPECT_THROW(SequenceTiming::synchronize(threeSpans(), 'z', 40.0, 1), std::runtime_error);
  EXPECT_THROW(SequenceTiming::synchronize({{'a', 10, 5}}, 'a', 40.0, 1), std::runtime_error);
}

TEST(SequenceConfig, TheTwelveCosmoBenchSequencesLoad) {
  const std::vector<std::pair<std::string, std::size_t>> expected{
      {"ntu_r3_00", 3},  {"ntu_r3_01", 3},  {"ntu_r3_02", 3},      {"ntu_r4_00", 4},
      {"ntu_r5_00", 5},  {"kth_r3_00", 3},  {"kth_r3_01", 3},      {"kth_r4_00", 4},
      {"tuhh_r3_00", 3}, {"tuhh_r3_01", 3}, {"kittredge_loop", 4}, {"main_campus", 4}};
  for (const auto& [name, robots] : expected) {
    const auto cfg = SequenceConfig::load(std::string(COSMO_SOURCE_DIR) + "/config/sequences/" + name + ".yaml");
    EXPECT_EQ(cfg.name, name);
    EXPECT_EQ(cfg.trials.size(), robots) << name;
    EXPECT_TRUE(std::filesystem::exists(cfg.noise_models)) << cfg.noise_models;
  }
  EXPECT_EQ(SequenceConfig::load(std::string(COSMO_SOURCE_DIR) + "/config/sequences/ntu_r3_00.yaml").trials[1].name,
            "ntu_night_04");
}
