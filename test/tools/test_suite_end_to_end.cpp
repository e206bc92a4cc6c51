// cosmo_suite as a user runs it, on a light CI-shaped suite (test/suite/ci_short.yaml: config/suites/ci.yaml's
// synthetic sequence at half the LiDAR columns in the MCD and CU-Multi layouts, both comm models, a noise-model
// estimate first; one seed, the reference odometry): every dataset present, valid and byte for byte what cosmo_generate writes when run alone on
// the same inputs; killed (SIGKILL) at a random moment and run again: the same bytes; a changed sequence file redoes
// exactly its datasets; a bad suite file stops before anything runs, naming the file and the key; a second suite on
// the same output folder is refused.
// The simulator's and the scan cache are the test's own (COSMO_SIM_CACHE, COSMO_SCAN_CACHE), so that it can change a
// sequence file without touching anyone else's.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <thread>

#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/suite/child_process.hpp"
#include "cosmo/suite/job_record.hpp"
#include "slurm_cluster.hpp"
#include "suite_end_to_end.hpp"

namespace fs = std::filesystem;
using namespace cosmo;
using namespace suite_e2e;

TEST_F(SuiteEndToEnd, EveryDatasetIsThereValidAndWhatCosmoGenerateWritesAlone) {
  const fs::path a = runA();
  for (const auto& g : groups()) {
    const fs::path dir = a / g.id;
    ASSERT_TRUE(fs::exists(dir / suite::kRecordFile)) << g.id;
    for (const char* comm : {"wifi", "proradio"}) {
      const fs::path jrl = dir / ("suite_light_" + std::string(comm) + ".jrl");
      ASSERT_TRUE(fs::exists(jrl)) << jrl;
      const jrl::Dataset d = jrl::readJrl(jrl.string());
      EXPECT_TRUE(jrl::validate(d).empty()) << jrl;
      EXPECT_TRUE(d.outliers.has_value()) << jrl << " is not labelled";
    }
  }
  EXPECT_TRUE(fs::exists(a / "manifest.jsonl"));
  std::ifstream manifest(a / "manifest.jsonl");
  std::size_t lines = 0;
  for (std::string l; std::getline(manifest, l);) ++lines;
  EXPECT_EQ(lines, groups().size() + 1);  // + the estimate
  const std::string html = cosmo::readWholeFileOrEmpty(a / "report.html");
  EXPECT_NE(html.find("data:image/svg+xml;base64,"), std::string::npos);
  EXPECT_EQ(html.find("src=\"ci_"), std::string::npos) << "the report reads figures from beside it";
  EXPECT_NE(cosmo::readWholeFileOrEmpty(a / "report.md").find("| ci_mcd_s2_odom-reference_wifi | done |"), std::string::npos);

  // the estimate and each group, by cosmo_generate alone into a folder of its own
  const fs::path alone = root() / "alone";
  const fs::path estimate = alone / "synthetic_cu.yaml";
  Outcome e = runTool("cosmo_generate", {sequence("cu-multi"), "--estimate-noise-models", "b", "--estimate-only",
                                     "--noise-models-out", estimate.string()});
  ASSERT_EQ(e.status, 0) << e.output;
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(estimate), cosmo::readWholeFileOrEmpty(a / "noise_models/synthetic_cu/synthetic_cu.yaml"));
  for (const auto& g : groups()) {
    const fs::path out = alone / g.id;
    std::vector<std::string> args{sequence(g.layout), "--comm", "wifi,proradio", "--seed", g.seed, "--odometry", "reference",
                                  "--out", out.string(), "--quiet"};
    if (g.layout == "cu-multi") args.insert(args.end(), {"--noise-models", (a / "noise_models/synthetic_cu/synthetic_cu.yaml").string()});
    const Outcome r = runTool("cosmo_generate", args);
    ASSERT_EQ(r.status, 0) << r.output;
    expectSameFiles(out, a / g.id);
  }
}

/// A random moment of a run: after the k-th job has started (k of 1..3) and a random delay of up to 1 s, which
/// falls inside a job, between jobs, or while a finished job moves into place.
TEST_F(SuiteEndToEnd, KilledAtARandomMomentAndRunAgainGivesTheSameBytes) {
  const ReferenceAside aside;  // the run goes into the reference's own output folder
  const fs::path a = aside.ref, b = aside.a;
  std::random_device rd;
  const unsigned seed = rd();
  std::mt19937 rng(seed);
  const int k = std::uniform_int_distribution<int>(1, 3)(rng);
  const double delay = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  std::printf("SIGKILL %.2f s after the start of job %d of 3 (random seed %u)\n", delay, k, seed);
  const fs::path log = root() / "killed.log";
  const pid_t pid = suite::spawnChild(suiteCommand(b, {"--jobs", "1"}), log.string());
  const auto started = [&] {
    const std::string text = cosmo::readWholeFileOrEmpty(log);
    int n = 0;
    for (std::size_t p = 0; (p = text.find("[suite] start ", p)) != std::string::npos; ++p) ++n;
    return n;
  };
  int status = 0;
  while (started() < k && ::waitpid(pid, &status, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::duration<double>(delay));
  // while it runs, a second suite on the same folder is refused
  const Outcome second = runTool("cosmo_suite", {ciSuite(), "--out", b.string()});
  ASSERT_EQ(::waitpid(pid, &status, WNOHANG), 0) << "the run ended before it could be killed:\n" << cosmo::readWholeFileOrEmpty(log);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(second.status, 2) << second.output;
  EXPECT_NE(second.output.find("is in use by another cosmo_suite"), std::string::npos) << second.output;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // its children die with it (PDEATHSIG)
  EXPECT_EQ(processesMentioning(b.string() + "/"), 0) << "a job of the killed suite still runs";
  const Outcome again = runTool("cosmo_suite", {ciSuite(), "--out", b.string(), "--jobs", "2"});
  ASSERT_EQ(again.status, 0) << again.output;
  std::printf("%s", again.output.substr(0, again.output.find("[suite] start")).c_str());
  EXPECT_NE(again.output.find("-> to do"), std::string::npos) << "nothing was left to redo";
  for (const auto& g : groups()) expectSameFiles(b / g.id, a / g.id);
  expectSameFiles(b / "noise_models/synthetic_cu", a / "noise_models/synthetic_cu");
}

TEST_F(SuiteEndToEnd, AChangedSequenceFileRedoesExactlyItsDatasets) {
  const fs::path a = runA();
  const fs::path seq = sequence("mcd");
  const std::string mcd = groups()[0].id, cu = groups()[1].id;
  const std::string original = cosmo::readWholeFileOrEmpty(seq), jrl = cosmo::readWholeFileOrEmpty(a / mcd / "suite_light_wifi.jrl");
  std::ofstream(seq, std::ios::app) << "# changed by the test\n";
  const Outcome r = runTool("cosmo_suite", {ciSuite(), "--out", a.string()});
  std::ofstream(seq, std::ios::trunc) << original;
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(mcd + ": stale: input changed: sequence " + seq.string() + " -> to do"), std::string::npos)
      << r.output;
  for (const std::string id : {std::string("noise_models/synthetic_cu"), cu})
    EXPECT_NE(r.output.find(id + ": current -> skipped"), std::string::npos) << id << "\n" << r.output;
  EXPECT_NE(r.output.find("4 datasets: 2 done, 2 skipped as current, 0 failed"), std::string::npos) << r.output;
  // a comment changes no output: the redone datasets are the same bytes
  EXPECT_TRUE(cosmo::readWholeFileOrEmpty(a / mcd / "suite_light_wifi.jrl") == jrl);
}

TEST_F(SuiteEndToEnd, ABadSuiteFileStopsBeforeAnythingRunsNamingTheFileAndTheKey) {
  const fs::path bad = root() / "bad_suite.yaml";
  std::ofstream(bad) << cosmo::readWholeFileOrEmpty(ciSuite()) << "  sed: [3]\n";
  const fs::path out = root() / "bad_out";
  const Outcome r = runTool("cosmo_suite", {bad.string(), "--out", out.string()});
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(bad.string() + ": variants.sed: unknown parameter (did you mean 'seed'?)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(SuiteEndToEnd, OnASingleNodeSlurmClusterTheOutputsAreThoseOfTheLocalRun) {
  runA();
  const SlurmCluster cluster(root() / "slurm");
  if (!cluster.whyNot().empty()) GTEST_SKIP() << "no Slurm here: " << cluster.whyNot();
  const ReferenceAside aside;
  const fs::path a = aside.ref, c = aside.a;
  const Outcome r = runTool("cosmo_suite", {ciSuite(), "--out", c.string(), "--slurm", "--wait"});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("submitted wave1: Slurm job"), std::string::npos) << r.output;  // after the estimate
  EXPECT_NE(r.output.find("4 datasets: 4 done, 0 skipped as current, 0 failed"), std::string::npos) << r.output;
  for (const auto& g : groups()) expectSameFiles(c / g.id, a / g.id);
  expectSameFiles(c / "noise_models/synthetic_cu", a / "noise_models/synthetic_cu");
  EXPECT_TRUE(fs::exists(c / "report.html"));
  const Outcome st = runTool("cosmo_suite", {"status", "--out", c.string()});
  EXPECT_NE(st.output.find(groups()[1].id + ": done"), std::string::npos) << st.output;
  // resumed under Slurm: everything current, nothing submitted
  const Outcome again = runTool("cosmo_suite", {ciSuite(), "--out", c.string(), "--slurm"});
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find(groups()[1].id + ": current -> skipped"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("submitted"), std::string::npos) << again.output;
}

/// cosmo_generate --estimate-noise-models on a sequence that names no noise models at all (no environment, no
/// file): the estimate is written beside the outputs, the output says where, and the dataset uses it.
TEST_F(SuiteEndToEnd, AnEstimateWithoutAModelFileIsWrittenBesideTheOutputsAndUsed) {
  const fs::path cached = sequence("cu-multi");
  std::string yaml = cosmo::readWholeFileOrEmpty(cached);
  yaml = std::regex_replace(yaml, std::regex("\nenvironment: [a-z_]+\n"), "\n");
  yaml = std::regex_replace(yaml, std::regex("\nname: suite_light\n"), "\nname: no_models\ndata_root: " +
                                                                           cached.parent_path().string() + "\n");
  ASSERT_EQ(yaml.find("environment"), std::string::npos);
  const fs::path seq = root() / "no_models.yaml", out = root() / "no_models_out";
  std::ofstream(seq) << yaml;
  const Outcome plain = runTool("cosmo_generate", {seq.string(), "--out", out.string(), "--quiet"});
  EXPECT_EQ(plain.status, 1) << plain.output;
  EXPECT_NE(plain.output.find("names no noise models"), std::string::npos) << plain.output;
  const Outcome r = runTool("cosmo_generate", {seq.string(), "--estimate-noise-models", "b", "--out", out.string(),
                                               "--max-seconds", "10", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path models = out / "no_models.noise_models.yaml";
  EXPECT_NE(r.output.find("wrote the estimate to " + models.string()), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(models));
  EXPECT_NE(cosmo::readWholeFileOrEmpty(models).find("from trial suite_b"), std::string::npos) << cosmo::readWholeFileOrEmpty(models);
  EXPECT_NE(cosmo::readWholeFileOrEmpty(out / "no_models_wifi.recorder.yaml").find(models.string()), std::string::npos);
}

/// The gate-threshold variant's option is the sequence's own `registration:` keys: `--gate-threshold 0.7` gives the
/// bytes of a copy of the sequence with `gate: strict`, `min_structure_overlap: 0.7`; a threshold outside [0, 1]
/// stops before anything runs, naming the option.
TEST_F(SuiteEndToEnd, TheGateThresholdOptionIsTheSequencesOwnKeys) {
  const fs::path cached = sequence("mcd");
  std::string yaml = cosmo::readWholeFileOrEmpty(cached);
  ASSERT_EQ(yaml.find("\nregistration:"), std::string::npos) << cached;
  yaml += "\ndata_root: " + cached.parent_path().string() + "\nregistration:\n  gate: strict\n  min_structure_overlap: 0.7\n";
  const fs::path keys_dir = root() / "gate_keys";
  fs::create_directories(keys_dir);
  std::ofstream(keys_dir / cached.filename()) << yaml;
  const std::vector<std::string> common{"--comm", "wifi", "--odometry", "reference", "--max-seconds", "12", "--quiet"};
  std::vector<std::string> with_keys{(keys_dir / cached.filename()).string(), "--out", (root() / "gate_a").string()};
  std::vector<std::string> with_option{cached.string(), "--gate-threshold", "0.7", "--out", (root() / "gate_b").string()};
  with_keys.insert(with_keys.end(), common.begin(), common.end());
  with_option.insert(with_option.end(), common.begin(), common.end());
  const Outcome a = runTool("cosmo_generate", with_keys), b = runTool("cosmo_generate", with_option);
  ASSERT_EQ(a.status, 0) << a.output;
  ASSERT_EQ(b.status, 0) << b.output;
  const std::string jrl = "suite_light_wifi.jrl";
  EXPECT_TRUE(cosmo::readWholeFileOrEmpty(root() / "gate_a" / jrl) == cosmo::readWholeFileOrEmpty(root() / "gate_b" / jrl));
  const Outcome bad = runTool("cosmo_generate", {cached.string(), "--gate-threshold", "1.5", "--out",
                                                 (root() / "gate_c").string()});
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("--gate-threshold: gate threshold (min_structure_overlap) must be in [0, 1]"),
            std::string::npos)
      << bad.output;
}
