// The recorder's session (dataset/recorder_session.hpp), the policy under the recorder node: nothing acknowledged is
// lost when the process dies (a new session replays the journal and drops what a sender sends again), another run's
// journal is never merged, and the dataset says whether it is complete; a complete one removes the journal.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "cosmo/dataset/recorder_session.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using namespace cosmo::dataset;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path dir;
  TempDir() {
    dir = fs::temp_directory_path() / ("cosmo_recorder_session_" + std::to_string(::getpid()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempDir() { fs::remove_all(dir); }
};

MeasurementRecord keyframe(char robot, std::uint64_t seq, std::uint32_t index) {
  KeyframeMeasurement k;
  k.robot = robot;
  k.index = index;
  k.stamp = 1000000000ULL * (index + 1);
  k.odometry.translation() = Eigen::Vector3d(2.0, 0, 0);
  k.reference = Pose3::Identity();
  k.reference->translation() = Eigen::Vector3d(2.0 * index, robot == 'a' ? 0.0 : 5.0, 0);
  return MeasurementRecord{robot, seq, k};
}

MeasurementRecord closure(char owner, std::uint64_t seq, std::uint32_t i, std::uint32_t j) {
  LoopClosureMeasurement lc;
  lc.owner = owner;
  lc.computed_at = 1000000000ULL * (i + 1);
  lc.key1 = jrl::symbol(owner, i);
  lc.key2 = jrl::symbol(owner, j);
  return MeasurementRecord{owner, seq, lc};
}

JournalHeader run(const std::string& id, bool with_player = true) { return {id, "team_wifi", {'a', 'b'}, with_player}; }

}  // namespace

TEST(RecorderSession, NothingAcknowledgedIsLostWhenTheProcessDies) {
  TempDir t;
  {
    RecorderSession s(t.dir.string(), run("run-1"), NoiseModels{}, OutlierRule::Fidelity);
    EXPECT_FALSE(s.opening().resumed);
    for (std::uint32_t i = 0; i < 5; ++i) EXPECT_TRUE(s.take(keyframe('a', i + 1, i)));
    EXPECT_TRUE(s.take(keyframe('b', 1, 0)));
    EXPECT_TRUE(s.take(closure('a', 6, 4, 0)));
    s.durable();  // the node acknowledges after this: a 1..6, b 1
    EXPECT_EQ(s.intake().acked('a'), 6u);
  }  // killed: never written
  RecorderSession again(t.dir.string(), run("run-1"), NoiseModels{}, OutlierRule::Fidelity);
  EXPECT_TRUE(again.opening().resumed);
  EXPECT_EQ(again.opening().records, 7u);
  EXPECT_EQ(again.sessions(), 2u);
  EXPECT_EQ(again.intake().acked('a'), 6u);
  EXPECT_EQ(again.intake().acked('b'), 1u);
  EXPECT_FALSE(again.take(keyframe('a', 3, 2)));  // a sender sends again what it did not see acknowledged: dropped
  EXPECT_TRUE(again.take(keyframe('b', 2, 1)));
  again.playerDone();
  again.end();
  EXPECT_TRUE(again.incomplete().empty());
  jrl::Dataset ds;
  const BuildReport report = again.write((t.dir / "team_wifi.jrl").string(), {{"name", "team"}}, &ds);
  EXPECT_EQ(report.keyframes_pending, 0u);
  EXPECT_GT(report.entries, 0u);
  const std::string meta = cosmo::readWholeFileOrEmpty(t.dir / "team_wifi.recorder.yaml");
  EXPECT_NE(meta.find("complete: true"), std::string::npos) << meta;
  EXPECT_NE(meta.find("recorder_sessions: 2"), std::string::npos) << meta;
  EXPECT_NE(meta.find("name: team"), std::string::npos) << meta;
  EXPECT_TRUE(fs::exists(again.journalPath()));
  EXPECT_TRUE(again.finish(true));
  EXPECT_FALSE(fs::exists(again.journalPath()));
}

TEST(RecorderSession, AResumedSessionKnowsThePlayerFinishedAndAnIncompleteRunKeepsItsJournal) {
  TempDir t;
  {
    RecorderSession s(t.dir.string(), run("run-2"), NoiseModels{}, OutlierRule::Fidelity);
    s.take(keyframe('a', 1, 0));
    s.playerDone();
    s.durable();
  }
  {  // started on its own (no player now): the journal says a player ran it and finished
    RecorderSession s(t.dir.string(), run("run-2", false), NoiseModels{}, OutlierRule::Fidelity);
    EXPECT_TRUE(s.run().with_player);
    EXPECT_TRUE(s.playerFinished());
    s.end();
    EXPECT_TRUE(s.incomplete().empty());
  }
  RecorderSession s(t.dir.string(), run("run-3"), NoiseModels{}, OutlierRule::Fidelity);  // another run
  EXPECT_FALSE(s.opening().resumed);
  EXPECT_EQ(s.opening().records, 0u);
  EXPECT_NE(s.opening().note.find("run-2"), std::string::npos) << s.opening().note;  // moved aside, not merged
  s.take(keyframe('a', 1, 0));
  EXPECT_TRUE(s.stop("the player stopped the run: frontend b died"));
  EXPECT_FALSE(s.stop("a second reason"));
  s.end();
  EXPECT_EQ(s.incomplete(), "the player stopped the run: frontend b died");
  s.frontendSkipped('b', 4);
  s.frontendSkipped('b', 2);
  EXPECT_EQ(s.scansSkipped('b'), 4u);
  const MetadataLines lines = s.metadata({});
  std::string all;
  for (const auto& [k, v] : lines) all += k + ": " + v + "\n";
  EXPECT_NE(all.find("complete: false"), std::string::npos) << all;
  EXPECT_NE(all.find("incomplete: \"the player stopped the run: frontend b died\""), std::string::npos) << all;
  EXPECT_NE(all.find("scans_skipped: {a: 0, b: 4}"), std::string::npos) << all;
  s.write((t.dir / "team_wifi.jrl").string(), {});
  EXPECT_FALSE(s.finish(true));  // incomplete: the journal stays for a rerun to look at
  EXPECT_TRUE(fs::exists(s.journalPath()));
}

TEST(RecorderSession, ARunWithAPlayerThatNeverFinishedIsIncomplete) {
  TempDir t;
  RecorderSession s(t.dir.string(), run("run-4"), NoiseModels{}, OutlierRule::Fidelity);
  s.end();
  EXPECT_EQ(s.incomplete(), "the run ended before the player finished the sequence (no /player/done)");
  RecorderSession live((t.dir / "live").string(), run("live", false), NoiseModels{}, OutlierRule::Fidelity);
  live.end();  // no player: complete when it ends
  EXPECT_TRUE(live.incomplete().empty());
}

TEST(RecorderSession, TheWrittenLineSaysWhatWasWrittenWhatIsNotLabelledAndWhatIsPending) {
  TempDir t;
  RecorderSession s(t.dir.string(), run("run-5"), NoiseModels{}, OutlierRule::Fidelity);
  BuildReport report;
  report.entries = 3;
  report.labelled = true;
  const std::string plain = s.writtenLine("x.jrl", "end of run", report);
  EXPECT_EQ(plain.rfind("wrote x.jrl (end of run): 3 entries; ", 0), 0u) << plain;
  EXPECT_EQ(plain.find("pending"), std::string::npos) << plain;

  report.labelled = false;
  report.labels_note = "no ground truth";
  report.keyframes_pending = 2;
  report.loop_closures_pending = 1;
  s.end();  // the player never finished: marked incomplete
  const std::string line = s.writtenLine("x.jrl", "end of run", report);
  EXPECT_EQ(line.rfind("wrote x.jrl (end of run, marked incomplete): 3 entries; ", 0), 0u) << line;
  EXPECT_NE(line.find("; no ground truth"), std::string::npos) << line;
  EXPECT_NE(line.find("; pending (not written yet): 2 keyframes, 1 loop closures"), std::string::npos) << line;
}
