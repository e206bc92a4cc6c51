// Suite files and their jobs: keys checked with the file, the key and the nearest name; the variant grid and
// the datasets' names; the noise-model estimate as a job the groups of its environment wait for; missing inputs
// all named before anything runs; the shipped suite files read.
#include <gtest/gtest.h>

#include <algorithm>

#include "cosmo/suite/plan.hpp"
#include "suite_fixture.hpp"

using namespace cosmo::suite;
using suite_test::Folder;

namespace {

std::string loadError(const Folder& f, const std::string& text) {
  const auto path = f.write("bad.yaml", text);
  try {
    SuiteFile::load(path.string());
  } catch (const std::exception& e) { return e.what(); }
  return "";
}

std::vector<std::string> ids(const Plan& p) {
  std::vector<std::string> out;
  for (const auto& j : p.jobs) out.push_back(j.id);
  return out;
}

}  // namespace

TEST(SuiteFile, AnUnknownVariantKeyNamesTheFileTheKeyAndTheNearestName) {
  Folder f;
  const std::string e = loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  sed: [1, 2]\n");
  EXPECT_NE(e.find("bad.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("variants.sed"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'seed'"), std::string::npos) << e;
  const std::string r = loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  radio.bandwith_kBps: [500]\n");
  EXPECT_NE(r.find("did you mean 'radio.bandwidth_kBps'"), std::string::npos) << r;
  const std::string g = loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  registration.min_overlp: [0.4]\n");
  EXPECT_NE(g.find("did you mean 'registration.min_overlap'"), std::string::npos) << g;
}

TEST(SuiteFile, UnknownKeysAndBadValuesElsewhereNameTheirPlace) {
  Folder f;
  EXPECT_NE(loadError(f, "sequence:\n  - sequence: x.yaml\n").find("did you mean 'sequences'"), std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequense: x.yaml\n").find("sequences[0].sequense"), std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  seed: [1, -2]\n").find("variants.seed[1]"),
            std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  odometry: lidar\n").find("loam or reference"),
            std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  registration.gate: [loose]\n")
                .find("variants.registration.gate"),
            std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  radio.d_init: [-3]\n").find("d_init"),
            std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  inject: [{rate: 2, kind: random}]\n")
                .find("rate"),
            std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\n    layout: kitti\n").find("layout"), std::string::npos);
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nnoise_models:\n  - estimate: e\n    frm: x\n")
                .find("did you mean 'from'"),
            std::string::npos);
}

TEST(SuitePlan, TheVariantGridNamesEveryGroupAndPassesItsOptions) {
  Folder f;
  suite_test::writeSequence(f, "seq", "alpha", 3, 20.0);
  const auto suite = f.write("s.yaml",
                             "name: t\ncomm: [wifi, proradio]\nmax_seconds: 12\nsequences:\n  - sequence: seq/alpha.yaml\n"
                             "variants:\n  seed: [1, 2]\n  odometry: [loam, reference]\n");
  const Plan plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
  EXPECT_EQ(ids(plan), (std::vector<std::string>{"alpha_s1_odom-loam", "alpha_s1_odom-reference", "alpha_s2_odom-loam",
                                                 "alpha_s2_odom-reference"}));
  const Job& j = plan.job("alpha_s2_odom-reference");
  EXPECT_EQ(j.datasetNames(), (std::vector<std::string>{"alpha_s2_odom-reference_wifi", "alpha_s2_odom-reference_proradio"}));
  EXPECT_EQ(j.request.sequence, (f.root / "seq/alpha.yaml").string());
  EXPECT_EQ(j.request.comms, (std::vector<std::string>{"wifi", "proradio"}));
  EXPECT_EQ(j.request.seed, 2u);
  EXPECT_EQ(j.request.max_seconds, 12.0);
  EXPECT_EQ(j.request.odometry, "reference");
  // what its process runs, and what the plan file keeps, reads back as the same request
  const std::vector<std::string> want{(f.root / "seq/alpha.yaml").string(), "--comm", "wifi,proradio", "--seed", "2",
                                      "--max-seconds", "12", "--odometry", "reference"};
  EXPECT_EQ(cosmo::pipeline::generateArgs(j.request), want);
  EXPECT_EQ(cosmo::pipeline::generateArgs(Plan::fromJson(plan.toJson(), "plan").job(j.id).request), want);
  EXPECT_EQ(j.robots, 3);
  EXPECT_NEAR(j.seconds, 12.0, 1e-9);  // min(reference span 20 s, max_seconds)
  EXPECT_EQ(j.jrlFile("wifi"), "alpha_wifi.jrl");
}

TEST(SuitePlan, RepeatsSeedFromTheSequencesOwnSeed) {
  Folder f;
  suite_test::writeSequence(f, "seq", "alpha", 2, 5.0);
  const auto suite = f.write("s.yaml", "sequences:\n  - sequence: seq/alpha.yaml\nvariants:\n  repeats: 2\n");
  const Plan plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
  ASSERT_EQ(ids(plan), (std::vector<std::string>{"alpha_r0", "alpha_r1"}));
  EXPECT_EQ(plan.jobs[0].request.seed, 3u);
  EXPECT_EQ(plan.jobs[1].request.seed, 4u);  // the sequence's seed 3 + 1
}

TEST(SuitePlan, ConfigVariantsGetTheirOwnConfigFolderAndMayNotOverrideTheSequence) {
  Folder f;
  suite_test::writeSequence(f, "seq", "alpha", 2, 5.0);
  suite_test::writeSequence(f, "own", "beta", 2, 5.0, "environment: synthetic\nregistration:\n  gate: paper\n");
  const auto suite = f.write("s.yaml", "sequences:\n  - sequence: seq/alpha.yaml\nvariants:\n  registration: [paper]\n"
                                       "  radio.bandwidth_kBps: [500]\n");
  const Plan plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
  const Job& j = plan.jobs.front();
  EXPECT_EQ(j.id, "alpha_reg-paper_bandwidth_kBps-500");
  EXPECT_EQ(j.registration.at("gate"), "paper");
  EXPECT_EQ(j.radio.at("bandwidth_kBps"), "500");
  EXPECT_EQ(j.request.config_dir.rfind(plan.out_dir + "/.suite/config/", 0), 0u) << j.request.config_dir;
  const auto clash = f.write("c.yaml", "sequences:\n  - sequence: own/beta.yaml\nvariants:\n  registration: [strict]\n");
  try {
    planSuite(SuiteFile::load(clash.string()), suite_test::planOptions(f));
    FAIL() << "a variant overrode the sequence's own registration key";
  } catch (const std::exception& e) { EXPECT_NE(std::string(e.what()).find("'gate' is set by the sequence"), std::string::npos) << e.what(); }
}

TEST(SuitePlan, TheEstimateIsAJobTheGroupsOfItsEnvironmentWaitFor) {
  Folder f;
  suite_test::writeSequence(f, "k", "kittredge", 4, 30.0, "environment: cu_boulder\n");
  suite_test::writeSequence(f, "m", "campus", 4, 30.0, "environment: cu_boulder\n");
  suite_test::writeSequence(f, "n", "ntu", 3, 30.0, "environment: ntu\n");
  const auto suite = f.write("s.yaml", "comm: [wifi, proradio]\nsequences:\n  - sequence: k/kittredge.yaml\n"
                                       "  - sequence: m/campus.yaml\n  - sequence: n/ntu.yaml\nnoise_models:\n"
                                       "  - estimate: cu_boulder\n    from: kittredge\n    trial: c\n");
  const Plan plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
  ASSERT_EQ(ids(plan), (std::vector<std::string>{"noise_models/cu_boulder", "kittredge", "campus", "ntu"}));
  const Job& e = plan.jobs[0];
  EXPECT_EQ(e.kind, Job::Kind::Estimate);
  EXPECT_EQ(cosmo::pipeline::generateArgs(e.request),
            (std::vector<std::string>{(f.root / "k/kittredge.yaml").string(), "--estimate-noise-models", "c",
                                      "--estimate-only"}));
  EXPECT_EQ(e.robots, 1);
  const std::string models = plan.out_dir + "/noise_models/cu_boulder/cu_boulder.yaml";
  for (const char* id : {"kittredge", "campus"}) {
    EXPECT_EQ(plan.job(id).depends_on, std::vector<std::string>{"noise_models/cu_boulder"}) << id;
    EXPECT_EQ(plan.job(id).request.noise_models, models);
  }
  EXPECT_TRUE(plan.job("ntu").depends_on.empty());
}

TEST(SuitePlan, AnEstimateFromAnUnknownSequenceNamesTheNearestLabel) {
  Folder f;
  suite_test::writeSequence(f, "k", "kittredge", 2, 5.0);
  const auto suite = f.write("s.yaml", "sequences:\n  - sequence: k/kittredge.yaml\nnoise_models:\n"
                                       "  - estimate: x\n    from: kitredge\n    trial: b\n");
  try {
    planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("noise_models[0].from: no sequence labelled 'kitredge' (did you mean "
                                         "'kittredge'?)"),
              std::string::npos)
        << e.what();
  }
}

TEST(SuitePlan, MissingTrialFilesAreAllNamedBeforeAnythingRuns) {
  Folder f;
  suite_test::writeSequence(f, "seq", "alpha", 2, 5.0);
  std::filesystem::remove(f.root / "seq/alpha_a.bag");
  std::filesystem::remove(f.root / "seq/alpha_b.txt");
  const auto suite = f.write("s.yaml", "sequences:\n  - sequence: seq/alpha.yaml\n");
  try {
    planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
    FAIL();
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("2 input file(s) do not exist"), std::string::npos) << m;
    EXPECT_NE(m.find("alpha_a.bag"), std::string::npos) << m;
    EXPECT_NE(m.find("alpha_b.txt"), std::string::npos) << m;
    EXPECT_NE(m.find("--data-root"), std::string::npos) << m;
  }
}

TEST(SuitePlan, ASequenceWithoutKnownNoiseModelsAndNoEstimateStops) {
  Folder f;
  suite_test::writeSequence(f, "k", "kittredge", 2, 5.0, "environment: cu_boulder\n");
  const auto suite = f.write("s.yaml", "sequences:\n  - sequence: k/kittredge.yaml\n");
  try {
    planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
    FAIL();
  } catch (const std::exception& e) { EXPECT_NE(std::string(e.what()).find("noise_models:"), std::string::npos) << e.what(); }
}

TEST(SuitePlan, ThePlanRoundTripsThroughJson) {
  Folder f;
  suite_test::writeSequence(f, "k", "kittredge", 2, 5.0);
  const auto suite = f.write("s.yaml", "comm: [wifi, proradio]\nsequences:\n  - sequence: k/kittredge.yaml\n"
                                       "noise_models:\n  - estimate: e\n    from: kittredge\n    trial: a\n"
                                       "    for: [kittredge]\nvariants:\n  inject: [{rate: 0.1, kind: group, seed: 2}]\n");
  const Plan plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
  EXPECT_EQ(plan.jobs[1].id, "kittredge_inj-group-0.1-s2");
  const Plan back = Plan::fromJson(plan.toJson(), "test");
  EXPECT_EQ(back.toJson(), plan.toJson());
  ASSERT_EQ(back.jobs[1].post_steps.size(), 1u);
  EXPECT_EQ(back.jobs[1].post_steps[0].verb, "inject");
}

TEST(SuitePlan, TheShippedSuitesRead) {
  const std::string dir = std::string(COSMO_SOURCE_DIR) + "/config/suites/";
  const SuiteFile ci = SuiteFile::load(dir + "ci.yaml");
  EXPECT_EQ(ci.sequences.size(), 2u);
  EXPECT_EQ(ci.comms, (std::vector<std::string>{"wifi", "proradio"}));
  const SuiteFile bench = SuiteFile::load(dir + "cosmo_bench.yaml");
  EXPECT_EQ(bench.sequences.size() * bench.comms.size(), 24u);
  ASSERT_EQ(bench.estimates.size(), 1u);
  EXPECT_EQ(bench.estimates[0].name, "cu_boulder");
  EXPECT_EQ(bench.estimates[0].from, "kittredge_loop");
  EXPECT_NE(bench.estimates[0].why.find("Kittredge Loop Robot 3"), std::string::npos);
}

/// The back-end controls as variants: the gate threshold passes `cosmo_generate --gate-threshold X` (on top of the
/// sequence's own registration keys, so a sequence that sets the gate may be swept), injected outliers a
/// `cosmo_jrl inject` step with every option; a bad threshold names its place; the threshold with a gate variant
/// stops.
TEST(SuitePlan, TheGateThresholdAndInjectedOutliersAreVariants) {
  Folder f;
  suite_test::writeSequence(f, "own", "beta", 2, 5.0, "environment: synthetic\nregistration:\n  gate: paper\n");
  const auto suite = f.write("s.yaml", "sequences:\n  - sequence: own/beta.yaml\nvariants:\n  gate_threshold: [0.45, 0.7]\n"
                                       "  inject: [{rate: 0.2, kind: group, seed: 3, group_size: 4, rate_of: all}]\n");
  const Plan plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
  ASSERT_EQ(ids(plan), (std::vector<std::string>{"beta_gate-0.45_inj-group-0.2-s3-g4-of-all",
                                                 "beta_gate-0.7_inj-group-0.2-s3-g4-of-all"}));
  const Job& j = plan.jobs[1];
  EXPECT_EQ(j.request.gate_threshold, 0.7);
  const std::vector<std::string> args = cosmo::pipeline::generateArgs(j.request);
  const auto gate = std::find(args.begin(), args.end(), "--gate-threshold");
  ASSERT_NE(gate, args.end());
  EXPECT_EQ(*(gate + 1), "0.7");
  EXPECT_TRUE(j.registration.empty());  // no config copy: the option goes on top of the sequence's keys
  ASSERT_EQ(j.post_steps.size(), 1u);
  EXPECT_EQ(j.post_steps[0].args, (std::vector<std::string>{"--rate", "0.2", "--kind", "group", "--seed", "3",
                                                            "--group-size", "4", "--rate-of", "all"}));
  const std::string bad = loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  gate_threshold: [0.5, 1.5]\n");
  EXPECT_NE(bad.find("variants.gate_threshold[1]: expected a threshold in [0, 1], got '1.5'"), std::string::npos) << bad;
  EXPECT_NE(loadError(f, "sequences:\n  - sequence: x.yaml\nvariants:\n  gate_treshold: [0.5]\n")
                .find("did you mean 'gate_threshold'"),
            std::string::npos);
  const auto both = f.write("b.yaml", "sequences:\n  - sequence: own/beta.yaml\nvariants:\n  gate_threshold: [0.5]\n"
                                      "  registration: [strict]\n");
  try {
    planSuite(SuiteFile::load(both.string()), suite_test::planOptions(f));
    FAIL() << "gate_threshold and a registration preset together";
  } catch (const std::exception& e) { EXPECT_NE(std::string(e.what()).find("not both"), std::string::npos) << e.what(); }
}

TEST(SuitePlan, TheShippedSweepReads) {
  const SuiteFile s = SuiteFile::load(std::string(COSMO_SOURCE_DIR) + "/config/suites/ci_controls.yaml");
  ASSERT_EQ(s.variants.size(), 2u);
  EXPECT_EQ(s.variants[0].key, "gate_threshold");
  EXPECT_EQ(s.variants[1].key, "inject");
  EXPECT_EQ(s.variants[1].values[0].scalar, "none");  // the baseline of the sweep: no step
  VariantEffect none;
  std::string sub;
  findVariantKey("inject", sub)->apply(sub, s.variants[1].values[0], none);
  EXPECT_TRUE(none.post_steps.empty());
}
