// Whether a job's folder is current: its record's inputs, parameters and outputs against the plan's; what makes it
// stale is named. The output folder's locks and the move into place.
#include <gtest/gtest.h>

#include <fstream>

#include "cosmo/suite/file_identity.hpp"
#include "cosmo/suite/job_record.hpp"
#include "cosmo/suite/out_dir.hpp"
#include "suite_fixture.hpp"

using namespace cosmo::suite;
using suite_test::Folder;
namespace fs = std::filesystem;

namespace {

/// A plan of one group and a folder for it that holds a current record (as a finished job leaves it).
struct Finished {
  Folder f;
  Plan plan;
  Finished() {
    suite_test::writeSequence(f, "seq", "alpha", 2, 5.0);
    const auto suite = f.write("s.yaml", "comm: [wifi, proradio]\nsequences:\n  - sequence: seq/alpha.yaml\n");
    plan = planSuite(SuiteFile::load(suite.string()), suite_test::planOptions(f));
    const Job& job = plan.jobs.front();
    const fs::path dir = jobFolder(plan, job);
    fs::create_directories(dir);
    std::ofstream(dir / "alpha_wifi.jrl") << "{}";
    JobRecord r;
    r.job = job.id;
    IdentityCache cache;
    r.inputs = inputIdentities(job, cache);
    r.key = jobKey(job, r.inputs);
    r.outputs.push_back({"alpha_wifi.jrl", 2, sha256File((dir / "alpha_wifi.jrl").string())});
    std::ofstream(dir / kRecordFile) << r.toJson() << "\n";
  }
  JobState state() {
    IdentityCache cache;
    return checkJob(plan, plan.jobs.front(), cache);
  }
};

}  // namespace

TEST(JobRecord, AFinishedFolderIsCurrent) {
  Finished d;
  EXPECT_EQ(d.state().kind, JobState::Kind::Current) << d.state().reason;
}

TEST(JobRecord, AChangedSequenceFileMakesItStaleAndSaysSo) {
  Finished d;
  std::ofstream(d.f.root / "seq/alpha.yaml", std::ios::app) << "# edited\n";
  const JobState s = d.state();
  EXPECT_EQ(s.kind, JobState::Kind::Stale);
  EXPECT_EQ(s.reason, "input changed: sequence " + (d.f.root / "seq/alpha.yaml").string());
}

TEST(JobRecord, AChangedTrialOrProgramMakesItStale) {
  Finished d;
  std::ofstream(d.f.root / "seq/alpha_b.bag", std::ios::app) << "more";
  EXPECT_NE(d.state().reason.find("bag b"), std::string::npos) << d.state().reason;
  Finished e;
  std::ofstream(e.f.root / "cosmo_generate", std::ios::app) << "rebuilt";
  EXPECT_NE(e.state().reason.find("program cosmo_generate"), std::string::npos) << e.state().reason;
}

TEST(JobRecord, AChangedOrMissingOutputMakesItStale) {
  Finished d;
  const fs::path jrl = fs::path(jobFolder(d.plan, d.plan.jobs.front())) / "alpha_wifi.jrl";
  std::ofstream(jrl) << "[]";
  EXPECT_EQ(d.state().reason, "output changed: alpha_wifi.jrl");
  fs::remove(jrl);
  EXPECT_EQ(d.state().reason, "output missing: alpha_wifi.jrl");
}

TEST(JobRecord, OtherParametersMakeItStale) {
  Finished d;
  d.plan.jobs.front().request.odometry = "reference";
  EXPECT_EQ(d.state().kind, JobState::Kind::Stale);
  EXPECT_EQ(d.state().reason, "parameters changed");
}

TEST(JobRecord, AFolderWithoutRecordIsStaleAndNoFolderIsMissing) {
  Finished d;
  fs::remove(fs::path(jobFolder(d.plan, d.plan.jobs.front())) / kRecordFile);
  EXPECT_EQ(d.state().kind, JobState::Kind::Stale);
  fs::remove_all(jobFolder(d.plan, d.plan.jobs.front()));
  EXPECT_EQ(d.state().kind, JobState::Kind::Missing);
}

TEST(JobRecord, RoundTripsThroughJson) {
  JobRecord r;
  r.job = "g";
  r.kind = "datasets";
  r.inputs = {{"sequence /a.yaml", "sha256:00"}};
  r.outputs = {{"x.jrl", 3, "ab"}};
  DatasetSummary s;
  s.name = "g_wifi";
  s.lc = 4;
  s.inliers_ate_m = 0.5;
  r.datasets = {s};
  r.wall_s = 1.5;
  const JobRecord back = JobRecord::fromJson(r.toJson(), "t");
  EXPECT_EQ(back.toJson(), r.toJson());
  EXPECT_EQ(back.datasets.at(0).lc, 4u);
}

TEST(FileIdentity, SmallFilesByContentLargeBySizeAndTimeFoldersByTheirFiles) {
  Folder f;
  const auto a = f.write("a.txt", "abc");
  EXPECT_EQ(fileIdentity(a.string()), "sha256:ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(fileIdentity((f.root / "none").string()), "missing");
  f.write("bag/metadata.yaml", "x");
  const std::string before = fileIdentity((f.root / "bag").string());
  EXPECT_EQ(before.rfind("folder:", 0), 0u);
  f.write("bag/bag_0.db3", "y");
  EXPECT_NE(fileIdentity((f.root / "bag").string()), before);
}

TEST(OutDir, ASecondSuiteOnTheSameOutputFolderIsRefusedWithAClearMessage) {
  Folder f;
  const auto first = lockOutDir(f.root.string(), "cosmo_suite first.yaml");
  try {
    lockOutDir(f.root.string(), "cosmo_suite second.yaml");
    FAIL() << "two suites held the lock";
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("is in use by another cosmo_suite"), std::string::npos) << m;
    EXPECT_NE(m.find("first.yaml"), std::string::npos) << m;
  }
  EXPECT_EQ(lockJob(f.root.string(), "noise_models/x", false) != nullptr, true);
}

TEST(OutDir, AFolderIsReplacedWholeAndAKilledWritersTmpFolderIsRemoved) {
  Folder f;
  const std::string out = f.root.string(), job = (f.root / "g").string();
  const std::string tmp1 = makeJobTmpDir(out, "g");
  std::ofstream(fs::path(tmp1) / "x") << "1";
  moveIntoPlace(out, tmp1, job);
  EXPECT_TRUE(fs::exists(fs::path(job) / "x"));
  const std::string tmp2 = makeJobTmpDir(out, "g");
  std::ofstream(fs::path(tmp2) / "y") << "2";
  moveIntoPlace(out, tmp2, job);
  EXPECT_FALSE(fs::exists(fs::path(job) / "x"));
  EXPECT_TRUE(fs::exists(fs::path(job) / "y"));
  EXPECT_TRUE(fs::is_empty(suiteDir(out, "trash")));
  makeJobTmpDir(out, "g");  // as a killed run leaves it
  EXPECT_TRUE(removePartial(out, "g"));
  EXPECT_FALSE(removePartial(out, "g"));
}
