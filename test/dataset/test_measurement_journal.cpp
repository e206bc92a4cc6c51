// The recorder's journal (dataset/measurement_journal.hpp): records come back bit-exact, a torn tail is cut off at
// its offset and the journal continues after the valid prefix, another run's journal is moved aside and never
// merged, and a damaged header is refused with a message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosmo/dataset/measurement_journal.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using namespace cosmo::dataset;

namespace {

class JournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = std::filesystem::temp_directory_path() / ("cosmo_journal_" + std::to_string(::getpid()) + "_" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    path = (dir / "run.journal").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::filesystem::path dir;
  std::string path;
  JournalHeader header{"run-1", "demo_wifi", {'a', 'b'}};
};

MeasurementRecord keyframe(char robot, std::uint64_t seq, std::uint32_t index) {
  KeyframeMeasurement k;
  k.robot = robot;
  k.index = index;
  k.stamp = 1700000000123456789ULL + index;
  k.odometry = makePose(0.1 * index, 1.0 / 3.0, -2.5, 0.01, 0.02, 1.0 / 7.0);
  if (index % 2 == 0) k.reference = makePose(1e5 + index, -3e4, 0.123456789, 0.3, -0.2, 2.0 / 3.0);
  if (index == 3) k.bridge_from = 1;
  k.scans_skipped = index * 2;
  return MeasurementRecord{robot, seq, k};
}

MeasurementRecord closure(char owner, std::uint64_t seq) {
  LoopClosureMeasurement lc;
  lc.owner = owner;
  lc.key1 = jrl::symbol(owner, 2);
  lc.key2 = jrl::symbol('b', 1);
  lc.computed_at = 1700000000987654321ULL;
  lc.measurement = makePose(0.7, -0.2, 0.1, 0.001, 0.002, 0.3);
  return MeasurementRecord{owner, seq, lc};
}

bool samePose(const Pose3& a, const Pose3& b) { return a.matrix() == b.matrix(); }

}  // namespace

TEST_F(JournalTest, RecordsComeBackBitExact) {
  const std::vector<MeasurementRecord> written{keyframe('a', 1, 0), keyframe('a', 2, 1), closure('a', 3),
                                               keyframe('b', 1, 3)};
  {
    MeasurementJournal j(path, header);
    for (const auto& r : written) j.append(r);
    EXPECT_EQ(j.pending(), 4u);
    j.sync();
    EXPECT_EQ(j.pending(), 0u);
  }
  const JournalContents c = readJournal(path);
  EXPECT_EQ(c.header.run_id, "run-1");
  EXPECT_EQ(c.header.name, "demo_wifi");
  EXPECT_EQ(c.header.robots, (std::vector<char>{'a', 'b'}));
  EXPECT_EQ(c.sessions, 1u);
  EXPECT_TRUE(c.tail_error.empty());
  EXPECT_EQ(c.valid_bytes, c.file_bytes);
  ASSERT_EQ(c.records.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_EQ(c.records[i].robot, written[i].robot);
    EXPECT_EQ(c.records[i].seq, written[i].seq);
    if (const auto* k = written[i].keyframe()) {
      const auto* back = c.records[i].keyframe();
      ASSERT_NE(back, nullptr);
      EXPECT_EQ(back->index, k->index);
      EXPECT_EQ(back->stamp, k->stamp);
      EXPECT_TRUE(samePose(back->odometry, k->odometry));
      ASSERT_EQ(back->reference.has_value(), k->reference.has_value());
      if (k->reference) { EXPECT_TRUE(samePose(*back->reference, *k->reference)); }
      EXPECT_EQ(back->bridge_from, k->bridge_from);
      EXPECT_EQ(back->scans_skipped, k->scans_skipped);
    } else {
      const auto* lc = written[i].loopClosure();
      const auto* back = c.records[i].loopClosure();
      ASSERT_NE(back, nullptr);
      EXPECT_EQ(back->owner, lc->owner);
      EXPECT_EQ(back->key1, lc->key1);
      EXPECT_EQ(back->key2, lc->key2);
      EXPECT_EQ(back->computed_at, lc->computed_at);
      EXPECT_TRUE(samePose(back->measurement, lc->measurement));
    }
  }
}

TEST_F(JournalTest, ThisRunsJournalIsResumedAndContinued) {
  {
    MeasurementJournal j(path, header);
    j.append(keyframe('a', 1, 0));
    j.sync();
  }
  MeasurementJournal::Opened opened;
  {
    MeasurementJournal j(path, header, &opened);
    j.append(keyframe('a', 2, 1));
    j.sync();
  }
  EXPECT_TRUE(opened.resumed);
  EXPECT_TRUE(opened.moved_to.empty());
  ASSERT_EQ(opened.contents.records.size(), 1u);
  const JournalContents c = readJournal(path);
  EXPECT_EQ(c.records.size(), 2u);
  EXPECT_EQ(c.sessions, 2u);
}

TEST_F(JournalTest, ATornTailIsCutOffAtItsOffsetAndTheJournalGoesOnAfterTheValidPrefix) {
  {
    MeasurementJournal j(path, header);
    j.append(keyframe('a', 1, 0));
    j.append(keyframe('a', 2, 1));
    j.sync();
  }
  const std::string whole = cosmo::readWholeFileOrEmpty(path);
  const std::string last = encodeJournalRecord(keyframe('a', 2, 1));
  const std::size_t last_at = whole.size() - last.size();
  // a SIGKILL in the middle of the last record's write
  std::filesystem::resize_file(path, whole.size() - 17);
  JournalContents c = readJournal(path);
  EXPECT_EQ(c.records.size(), 1u);
  EXPECT_EQ(c.valid_bytes, last_at);
  EXPECT_NE(c.tail_error.find("record at byte " + std::to_string(last_at)), std::string::npos) << c.tail_error;

  MeasurementJournal::Opened opened;
  {
    MeasurementJournal j(path, header, &opened);
    j.append(keyframe('a', 2, 1));
    j.sync();
  }
  EXPECT_TRUE(opened.resumed);
  EXPECT_NE(opened.note.find("torn tail"), std::string::npos) << opened.note;
  c = readJournal(path);
  EXPECT_TRUE(c.tail_error.empty()) << c.tail_error;
  EXPECT_EQ(c.records.size(), 2u);
  EXPECT_EQ(c.sessions, 2u);
}

TEST_F(JournalTest, ACorruptRecordEndsTheValidPrefix) {
  {
    MeasurementJournal j(path, header);
    for (std::uint64_t s = 1; s <= 3; ++s) j.append(keyframe('a', s, static_cast<std::uint32_t>(s - 1)));
    j.sync();
  }
  std::string bytes = cosmo::readWholeFileOrEmpty(path);
  const std::string one = encodeJournalRecord(keyframe('a', 3, 2));
  bytes[bytes.size() - one.size() / 2] ^= 0x40;  // a bit flipped inside the last record
  const JournalContents c = parseJournal(bytes, "flipped");
  EXPECT_EQ(c.records.size(), 2u);
  EXPECT_NE(c.tail_error.find("CRC mismatch"), std::string::npos) << c.tail_error;
}

TEST_F(JournalTest, AnotherRunsJournalIsMovedAsideNeverMerged) {
  {
    MeasurementJournal j(path, JournalHeader{"run-0", "demo_wifi", {'a', 'b'}});
    j.append(keyframe('a', 1, 0));
    j.sync();
  }
  MeasurementJournal::Opened opened;
  { MeasurementJournal j(path, header, &opened); }
  EXPECT_FALSE(opened.resumed);
  EXPECT_TRUE(opened.contents.records.empty());
  EXPECT_EQ(opened.moved_to, path + ".run-0.old");
  EXPECT_NE(opened.note.find("run 'run-0'"), std::string::npos) << opened.note;
  EXPECT_EQ(readJournal(opened.moved_to).records.size(), 1u) << "kept, aside";
  const JournalContents fresh = readJournal(path);
  EXPECT_EQ(fresh.header.run_id, "run-1");
  EXPECT_TRUE(fresh.records.empty());
}

TEST_F(JournalTest, ADamagedHeaderIsRefusedWithAMessageAndMovedAside) {
  std::ofstream(path, std::ios::binary) << "COSMOJNL\x01";
  EXPECT_THROW(
      {
        try {
          readJournal(path);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
          throw;
        }
      },
      std::runtime_error);
  EXPECT_THROW(parseJournal("not a journal at all", "x"), std::runtime_error);
  std::string bad = encodeJournalHeader(header);
  bad[12] ^= 1;  // header length
  EXPECT_THROW(parseJournal(bad, "x"), std::runtime_error);
  MeasurementJournal::Opened opened;
  { MeasurementJournal j(path, header, &opened); }
  EXPECT_EQ(opened.moved_to, path + ".unreadable.old");
  EXPECT_EQ(readJournal(path).header.run_id, "run-1");
}

TEST_F(JournalTest, EveryTruncationParsesWithoutThrowingPastTheHeader) {
  std::string bytes = encodeJournalHeader(header);
  const std::size_t header_size = bytes.size();
  for (std::uint64_t s = 1; s <= 4; ++s) bytes += encodeJournalRecord(keyframe('a', s, static_cast<std::uint32_t>(s)));
  bytes += encodeJournalRecord(closure('b', 1));
  for (std::size_t n = header_size; n <= bytes.size(); ++n) {
    const JournalContents c = parseJournal(std::string_view(bytes).substr(0, n), "cut");
    EXPECT_LE(c.valid_bytes, n);
    EXPECT_EQ(c.tail_error.empty(), c.valid_bytes == n);
  }
}
