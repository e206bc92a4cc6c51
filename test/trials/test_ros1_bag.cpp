// cosmo's own ROS 1 bag reader (trials/ros1_bag.hpp) against librosbag: the same scans bit for bit from bags
// written by rosbag (chunks none, bz2, lz4; the MCD layout; with and without decompression workers), the same
// message order when connections tie; and damaged bags — among them the MCD bag whose chunk-info `count` made
// librosbag die with SIGBUS in the pre-flight probe — end with a message naming the file, the byte offset, the
// record and what to do, never a signal.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosmo/ros/bag_io.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/ros/trial_layout_writer.hpp"
#include "cosmo/trials/trial_probe.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/trials/bag_format.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/trial_scans.hpp"

#include "tiny_trial.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

constexpr const char* kTopic = "/os_cloud_node/points";

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cosmo_ros1_bag_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::vector<Scan> tinyScans(int count, int beams = 16, int columns = 128) {
  const sim::LidarModel lidar = test::smallLidar(beams, columns, 10.0);
  const sim::PlannedSequence plan = test::tinyPlan(lidar);
  const auto& t = plan.trials.at(0);
  sim::ScanSimulator simulator(*plan.world, lidar);
  std::vector<Scan> scans;
  for (int k = 0; k < count; ++k)
    scans.push_back(simulator.simulate(t.body, t.params.extrinsicPose(), t.scan_stamps[k], t.noise_seed));
  return scans;
}

std::string writeBag(const fs::path& dir, const std::string& name, ros_glue::BagCompression compression, int scans) {
  const std::string path = (dir / name).string();
  ros_glue::ScanBagWriter bag(path, compression);
  for (const Scan& s : tinyScans(scans)) bag.write(kTopic, s, "os_sensor");
  return path;
}

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Every scan, layout and count of `ours` equals librosbag's, bit for bit.
void expectSameAsLibrosbag(const std::string& bag, bool stamp_at_end, int threads) {
  trials::Ros1ScanSource ours(bag, kTopic, stamp_at_end, threads);
  ros_glue::RosbagScanReader theirs(bag, kTopic, stamp_at_end);
  ASSERT_EQ(ours.size(), theirs.size());
  Scan a, b;
  std::size_t n = 0;
  while (theirs.next(b)) {
    ASSERT_TRUE(ours.next(a)) << n;
    EXPECT_EQ(a.stamp, b.stamp) << n;
    EXPECT_TRUE(sameBytes(a.points, b.points) && sameBytes(a.intensity, b.intensity) && sameBytes(a.time, b.time) &&
                sameBytes(a.ring, b.ring))
        << bag << " scan " << n;
    EXPECT_EQ(trials::describeFields(ours.lastLayout()), trials::describeFields(theirs.lastLayout()));
    EXPECT_EQ(ours.lastLayout().stamp, theirs.lastLayout().stamp);
    EXPECT_EQ(ours.lastCounts().points, theirs.lastCounts().points);
    EXPECT_EQ(ours.lastCounts().invalid, theirs.lastCounts().invalid);
    ++n;
  }
  EXPECT_FALSE(ours.next(a));
  EXPECT_GT(n, 0u);
}

void spit(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

/// The message of what reading `path` as a trial throws (Ros1Bag, then the scans).
std::string readError(const std::string& path) {
  try {
    trials::Ros1ScanSource source(path, kTopic);
    Scan s;
    while (source.next(s)) {
    }
  } catch (const std::runtime_error& e) { return e.what(); }
  return "";
}

/// The byte offset of the uint32 value of field `count` in the first record of op `op` (a record's fields are
/// in name order: ..., count, ..., op, ...).
std::size_t countOffset(const std::string& bytes, char op) {
  const std::size_t at = bytes.find(std::string("op=") + op);
  const std::size_t count = bytes.rfind("count=", at);
  EXPECT_NE(at, std::string::npos);
  EXPECT_NE(count, std::string::npos);
  return count + 6;
}

/// `bytes` with the uint32 at `at` set to `value`, written to `dir/name`; returns the path.
std::string mutated(const fs::path& dir, const std::string& name, std::string bytes, std::size_t at,
                    std::uint32_t value) {
  std::memcpy(&bytes[at], &value, 4);
  const std::string path = (dir / name).string();
  spit(path, bytes);
  return path;
}

/// What cosmo_generate's pre-flight check (the probe of the first scans) and synchronisation (the span) say about
/// `path`: both must end with a message naming the file, the record at its byte offset, the field and what to do.
void expectMessageFromProbeAndSpan(const std::string& path, const std::string& record, const std::string& field) {
  const std::string error = readError(path);
  EXPECT_NE(error.find(path + ": " + record + " record at byte "), std::string::npos) << error;
  EXPECT_NE(error.find(field), std::string::npos) << error;
  EXPECT_NE(error.find("rosbag reindex " + path), std::string::npos) << error;
  sequence::TrialConfig trial;
  trial.bag = path;
  trial.topic = kTopic;
  const sequence::TrialProbe probe = trials::probeTrial(trial);
  EXPECT_NE(probe.error.find(record + " record at byte"), std::string::npos) << probe.error;
  EXPECT_THROW(trials::readTrialSpan(trial), trials::Ros1BagError);
}

}  // namespace

TEST(Ros1Bag, SameScansAsLibrosbagForEveryCompression) {
  TempDir dir;
  for (auto [name, c] : {std::pair{"none.bag", ros_glue::BagCompression::None},
                         std::pair{"bz2.bag", ros_glue::BagCompression::Bz2},
                         std::pair{"lz4.bag", ros_glue::BagCompression::Lz4}}) {
    const std::string bag = writeBag(dir.path, name, c, 12);
    for (int threads : {0, 1, 3}) expectSameAsLibrosbag(bag, true, threads);
    expectSameAsLibrosbag(bag, false, 2);
  }
}

TEST(Ros1Bag, SameScansAsLibrosbagInTheMcdLayout) {
  TempDir dir;
  const sim::LidarModel lidar = test::smallLidar(16, 128, 10.0);
  const sim::PlannedSequence plan = test::tinyPlan(lidar);
  const auto& t = plan.trials.at(0);
  ros_glue::LayoutTrialInfo info;
  info.name = t.params.name;
  info.platform = t.params.platform;
  info.beams = 16;
  info.columns = 128;
  auto writer = ros_glue::makeTrialLayoutWriter(ros_glue::TrialLayout::Mcd, dir.path.string(), info);
  for (const Scan& s : tinyScans(20)) writer->write(s);  // MCD's reference needs > 1.5 s of scans
  const ros_glue::WrittenTrial w = writer->finish(t.body, t.params.extrinsicPose());
  const std::string bag = (dir.path / w.bag).string();
  EXPECT_TRUE(trials::ros1ChunksCompressed(bag));
  for (int threads : {0, 4}) expectSameAsLibrosbag(bag, w.stamp_at_end, threads);
}

TEST(Ros1Bag, TiesBetweenConnectionsComeInLibrosbagsOrder) {
  TempDir dir;
  const std::string path = (dir.path / "ties.bag").string();
  {
    const std::vector<Scan> scans = tinyScans(3, 2, 8);
    ros_glue::ScanBagWriter writer(path);
    for (int round = 0; round < 3; ++round)
      for (const char* topic : {"/c", "/a", "/b", "/a"}) writer.write(topic, scans[round], "frame");
  }
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::vector<std::pair<std::string, StampNs>> theirs, ours;
  for (const auto& m : view) theirs.emplace_back(m.getTopic(), m.getTime().toNSec());
  const trials::Ros1Bag own(path);
  std::vector<std::uint32_t> ids;
  for (const auto& c : own.connections()) ids.push_back(c.id);
  for (const auto& m : own.messages(ids)) ours.emplace_back(own.connection(m.connection).topic, m.received);
  EXPECT_EQ(ours, theirs);
  EXPECT_EQ(ours.size(), 12u);
}

TEST(Ros1Bag, IndexCountsOfAnMcdBagEndWithAMessage) {
  // librosbag died with SIGBUS in rosbag::Bag::readHeaderFromBuffer (from the bag reader's next() in the pre-flight
  // probe of cosmo_generate) on an MCD-layout bag whose first index data record's `count` was 2 instead of 1: it
  // read the next record's bytes as a second index entry, whose offset lies 1.8 GB past the chunk. The same with
  // the chunk info's `count`.
  TempDir dir;
  const std::string bytes = cosmo::readWholeFileOrEmpty(writeBag(dir.path, "good.bag", ros_glue::BagCompression::Bz2, 3));
  for (std::uint32_t count : {2u, 0u, 1000u, 0xffffffffu}) {
    const std::string tag = std::to_string(count) + ".bag";
    expectMessageFromProbeAndSpan(mutated(dir.path, "index_" + tag, bytes, countOffset(bytes, '\x04'), count),
                                  "index data", "'count'");
    expectMessageFromProbeAndSpan(mutated(dir.path, "chunk_info_" + tag, bytes, countOffset(bytes, '\x06'), count),
                                  "chunk info", "'count'");
  }
}

TEST(Ros1Bag, DamagedBagsEndWithAMessageNamingTheRecord) {
  TempDir dir;
  const std::string good = writeBag(dir.path, "good.bag", ros_glue::BagCompression::Bz2, 3);
  const std::string bytes = cosmo::readWholeFileOrEmpty(good);
  auto damaged = [&](const std::string& name, std::string mutated) {
    const std::string path = (dir.path / name).string();
    spit(path, mutated);
    return readError(path);
  };
  // Truncated: the index at the end is gone.
  EXPECT_NE(damaged("truncated.bag", bytes.substr(0, bytes.size() / 2)).find("truncated"), std::string::npos);
  // Not closed: index_pos 0.
  std::string unindexed = bytes;
  const std::size_t index_pos = unindexed.find("index_pos=") + 10;
  std::memset(&unindexed[index_pos], 0, 8);
  const std::string e1 = damaged("unindexed.bag", unindexed);
  EXPECT_NE(e1.find("bag header record at byte 13: index_pos is 0"), std::string::npos) << e1;
  EXPECT_NE(e1.find("rosbag reindex"), std::string::npos) << e1;
  // A damaged bz2 stream inside the first chunk.
  std::string flipped = bytes;
  const std::size_t bz = flipped.find("BZh");
  for (std::size_t i = bz + 40; i < bz + 60; ++i) flipped[i] = static_cast<char>(~flipped[i]);
  const std::string e2 = damaged("flipped.bag", flipped);
  EXPECT_NE(e2.find("chunk record at byte"), std::string::npos) << e2;
  EXPECT_NE(e2.find("rosbag check"), std::string::npos) << e2;
  // Not a bag at all.
  EXPECT_NE(damaged("text.bag", "hello").find("not a ROS 1 bag"), std::string::npos);
}

TEST(Ros1Bag, AMissingTopicListsTheBagsTopics) {
  TempDir dir;
  const std::string bag = writeBag(dir.path, "none.bag", ros_glue::BagCompression::None, 2);
  try {
    trials::Ros1ScanSource source(bag, "/velodyne_points");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("it has: /os_cloud_node/points (sensor_msgs/PointCloud2)"), std::string::npos)
        << e.what();
  }
}

TEST(Ros1Bag, ABagThatRecordsNothingReadsAsARecordingOfNothing) {
  TempDir dir;
  const std::string path = (dir.path / "empty.bag").string();
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);  // closed without a message, as `rosbag record` stopped at once
  }
  const trials::Ros1Bag ours(path);
  EXPECT_TRUE(ours.connections().empty());
  sequence::TrialConfig trial;
  trial.bag = path;
  trial.topic = kTopic;
  const sequence::TrialProbe probe = trials::probeTrial(trial);
  EXPECT_EQ(probe.bag, sequence::BagState::Empty) << probe.error;
  EXPECT_NE(probe.error.find("records nothing"), std::string::npos) << probe.error;

  // index_pos at the end of the file but connections announced: the index is missing, the bag damaged.
  std::string bytes = cosmo::readWholeFileOrEmpty(path);
  const std::size_t conn_count = bytes.find("conn_count=") + 11;
  bytes[conn_count] = 1;
  const std::string announced = (dir.path / "announced.bag").string();
  spit(announced, bytes);
  EXPECT_NE(readError(announced).find("the file is truncated"), std::string::npos) << readError(announced);
  trial.bag = announced;
  EXPECT_EQ(trials::probeTrial(trial).bag, sequence::BagState::Damaged);
}

TEST(Ros1Bag, TheCheckNamesWhatIsWrongWithATrialsBag) {
  TempDir dir;
  sequence::TrialConfig trial;
  trial.name = "t";
  trial.topic = kTopic;
  auto check = [&](const std::string& bag) {
    trial.bag = bag;
    const sequence::TrialProbe probe = trials::probeTrial(trial);
    return std::make_pair(probe.bag, sequence::checkTrial(trial, probe, {}, "", "").line);
  };
  const auto missing = check((dir.path / "nowhere.bag").string());
  EXPECT_EQ(missing.first, sequence::BagState::Missing);
  EXPECT_NE(missing.second.find("bag NOT FOUND"), std::string::npos) << missing.second;

  const std::string empty_file = (dir.path / "zero.bag").string();
  spit(empty_file, "");
  const auto zero = check(empty_file);
  EXPECT_EQ(zero.first, sequence::BagState::NotABag);
  EXPECT_NE(zero.second.find("NOT A BAG"), std::string::npos) << zero.second;

  const std::string text = (dir.path / "text.bag").string();
  spit(text, "hello, not a bag");
  EXPECT_EQ(check(text).first, sequence::BagState::NotABag);

  const std::string good = writeBag(dir.path, "good.bag", ros_glue::BagCompression::None, 2);
  const std::string truncated = (dir.path / "truncated.bag").string();
  const std::string bytes = cosmo::readWholeFileOrEmpty(good);
  spit(truncated, bytes.substr(0, bytes.size() / 2));
  const auto damaged = check(truncated);
  EXPECT_EQ(damaged.first, sequence::BagState::Damaged);
  EXPECT_NE(damaged.second.find("bag DAMAGED"), std::string::npos) << damaged.second;

  const auto folder = check(dir.path.string());  // a folder without .db3 files
  EXPECT_EQ(folder.first, sequence::BagState::NotABag);

  const auto ok = check(good);
  EXPECT_EQ(ok.first, sequence::BagState::Ok);
  EXPECT_NE(ok.second.find("bag ok"), std::string::npos) << ok.second;
}
