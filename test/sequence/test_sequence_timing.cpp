// Sequence config loading and the temporal synchronization of spec section 3.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/sim/simulation_params.hpp"

using namespace cosmo;
using namespace cosmo::frontend;
using namespace cosmo::sequence;

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

namespace {

const char* kTwoTrials = R"(
trials:
  - robot: a
    bag: a.bag
  - robot: b
    bag: b.bag
)";

}  // namespace

TEST(SequenceConfig, RegistrationKeysGoOnTopOfTheConfigFolderAndReachRegistrationParams) {
  const auto dir = std::filesystem::temp_directory_path() / "cosmo_pipeline_test" / "reg_config";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "registration.yaml") << "registration:\n  icp_iterations: 7\n  refine: true\n  gate: strict\n"
                                              "  min_overlap: 0.4\n";
  const auto plain = SequenceConfig::load(writeTemp("seq_reg_none.yaml", std::string("name: s\n") + kTwoTrials));
  EXPECT_TRUE(plain.registration.empty());
  const registration::RegistrationParams folder = plain.registrationParams(dir.string());
  EXPECT_TRUE(folder.refine);
  EXPECT_EQ(folder.gate, "strict");
  EXPECT_EQ(folder.icp_iterations, 7);
  EXPECT_DOUBLE_EQ(folder.min_overlap, 0.4);

  const auto paper = SequenceConfig::load(writeTemp(
      "seq_reg_paper.yaml", std::string("name: s\nregistration:\n  refine: false\n  gate: paper\n") + kTwoTrials));
  ASSERT_EQ(paper.registration.size(), 2u);
  const registration::RegistrationParams p = paper.registrationParams(dir.string());
  EXPECT_FALSE(p.refine);
  EXPECT_EQ(p.gate, "paper");
  EXPECT_DOUBLE_EQ(p.min_overlap, 0.0);  // the paper gate: KISS-Matcher's own checks only
  EXPECT_DOUBLE_EQ(p.min_structure_overlap, 0.0);
  EXPECT_EQ(p.icp_iterations, 7);  // every other key stays the folder's

  // The same keys handed over without the sequence (the front-end nodes get them as a parameter).
  const registration::RegistrationParams handed =
      registrationParamsWith(dir.string(), paper.registration, "the player");
  EXPECT_FALSE(handed.refine);
  EXPECT_EQ(handed.gate, "paper");
  EXPECT_EQ(handed.icp_iterations, 7);
  EXPECT_THROW(registrationParamsWith(dir.string(), {{"refien", "false"}}, "the player"), std::runtime_error);

  // Without a registration.yaml in the folder: the compiled-in defaults, then the sequence's keys.
  const auto empty_dir = std::filesystem::temp_directory_path() / "cosmo_pipeline_test" / "reg_empty";
  std::filesystem::create_directories(empty_dir);
  std::filesystem::remove(empty_dir / "registration.yaml");
  EXPECT_FALSE(paper.registrationParams(empty_dir.string()).refine);
  EXPECT_EQ(paper.registrationParams(empty_dir.string()).icp_iterations,
            registration::RegistrationParams{}.icp_iterations);

  // The shipped folder: a sequence without the key gets what every front-end gets from it.
  const registration::RegistrationParams shipped = plain.registrationParams(defaultConfigDir());
  const registration::RegistrationParams front = frontend::FrontendParams::loadDir(defaultConfigDir()).registration;
  EXPECT_EQ(shipped.refine, front.refine);
  EXPECT_EQ(shipped.gate, front.gate);
  EXPECT_DOUBLE_EQ(shipped.min_structure_overlap, front.min_structure_overlap);
}

TEST(SequenceConfig, ARegistrationKeyNobodyReadsOrABadValueNamesTheFileAndKey) {
  for (const char* section : {"registration:\n  refien: false\n", "registration:\n  gate: loose\n",
                              "registration:\n  refine: [false]\n", "registration: paper\n"}) {
    const auto path = writeTemp("seq_reg_bad.yaml", std::string("name: s\n") + section + kTwoTrials);
    try {
      SequenceConfig::load(path);
      ADD_FAILURE() << "accepted: " << section;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("registration"), std::string::npos) << what;
    }
  }
}

TEST(SequenceConfig, TheDemoWritesThePaperRegistrationIntoItsSequenceAndTheCiSequenceNone) {
  const std::string sim_dir = std::string(COSMO_SOURCE_DIR) + "/config/sim/";
  const auto demo = sim::SimulationParams::load(sim_dir + "default.yaml");
  const std::string demo_path = writeTemp("demo_seq.yaml", "");
  sim::writeSequenceConfig(demo_path, demo);
  const registration::RegistrationParams p = SequenceConfig::load(demo_path).registrationParams(defaultConfigDir());
  EXPECT_FALSE(p.refine);
  EXPECT_EQ(p.gate, "paper");
  EXPECT_NE(demo.describe().find("registration:"), std::string::npos);  // part of the cache key

  const auto ci = sim::SimulationParams::load(sim_dir + "ci.yaml");
  EXPECT_TRUE(ci.registration.empty());
  EXPECT_EQ(ci.describe().find("registration"), std::string::npos);  // its cache key is unchanged
  const std::string ci_path = writeTemp("ci_seq.yaml", "");
  sim::writeSequenceConfig(ci_path, ci);
  EXPECT_TRUE(SequenceConfig::load(ci_path).registration.empty());
}
