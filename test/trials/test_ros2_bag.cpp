// ROS 2 sqlite3 bags (trials/ros2_bag.hpp, trials/trial_scans.hpp): written and read back without ROS 2,
// topic spellings, missing topics, bad files, truncated messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <stdexcept>

#include "cosmo/trials/cdr_point_cloud.hpp"
#include "cosmo/trials/cu_multi_layout.hpp"
#include "cosmo/trials/ros2_bag.hpp"
#include "cosmo/trials/trial_scans.hpp"

using namespace cosmo;
using namespace cosmo::trials;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cosmo_ros2_bag_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

RawCloud cloudAt(StampNs stamp, int n) {
  OusterSweep sw;
  sw.beams = 2;
  sw.columns = 4;
  sw.stamp_at_end = false;
  sw.ring_uint16 = true;
  RawCloud c;
  c.layout = ousterLayout(sw);
  c.layout.stamp = stamp;
  c.data.assign(8 * 48, 0);
  for (int i = 0; i < n && i < 8; ++i) {  // the first n pixels are returns
    const float x = 1.0f + i;
    std::memcpy(c.data.data() + i * 48, &x, 4);
    const std::uint32_t range = 1000 + i;
    std::memcpy(c.data.data() + i * 48 + 32, &range, 4);
  }
  return c;
}

/// A bag folder "<dir>/robot1_x_lidar" with 5 clouds and an IMU-like topic.
fs::path writeBag(const fs::path& dir) {
  const fs::path folder = dir / "robot1_x_lidar";
  Ros2BagWriter w(folder.string());
  const int points = w.addTopic("robot1/ouster/points", "sensor_msgs/msg/PointCloud2");
  const int imu = w.addTopic("robot1/ouster/imu", "sensor_msgs/msg/Imu");
  for (int k = 0; k < 5; ++k) {
    const StampNs s = 1700000000000000000ULL + k * 50000000ULL;
    w.write(points, s + 1000, encodeCdrPointCloud2(cloudAt(s, 3 + k)));
    w.write(imu, s + 2000, {0, 1, 0, 0, 1, 2, 3});
  }
  w.close();
  return folder;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) { return e.what(); }
  return "";
}

}  // namespace

TEST(Ros2Bag, WrittenFolderHasMetadataAndOneDb3) {
  TempDir d;
  const fs::path folder = writeBag(d.path);
  EXPECT_TRUE(fs::exists(folder / "metadata.yaml"));
  EXPECT_TRUE(fs::exists(folder / "robot1_x_lidar_0.db3"));
  const auto files = ros2BagFiles(folder.string());
  ASSERT_EQ(files.size(), 1u);
  const auto topics = listRos2Topics(folder.string());
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "robot1/ouster/points");
  EXPECT_EQ(topics[0].type, "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(topics[0].serialization_format, "cdr");
  EXPECT_EQ(topics[0].messages, 5u);
}

TEST(Ros2Bag, ScansReadBackInOrderFromTheFolderOrItsDb3WithEitherTopicSpelling) {
  TempDir d;
  const fs::path folder = writeBag(d.path);
  for (const std::string& bag : {folder.string(), (folder / "robot1_x_lidar_0.db3").string()})
    for (const char* topic : {"robot1/ouster/points", "/robot1/ouster/points"}) {
      Ros2ScanSource src(bag, topic, false);
      EXPECT_EQ(src.size(), 5u);
      Scan s;
      for (int k = 0; k < 5; ++k) {
        ASSERT_TRUE(src.next(s)) << bag << " " << topic;
        EXPECT_EQ(s.stamp, 1700000000000000000ULL + k * 50000000ULL);
        EXPECT_EQ(s.size(), static_cast<std::size_t>(3 + k));  // the (0,0,0) pixels are dropped
        EXPECT_EQ(src.lastCounts().points, 8u);
        EXPECT_EQ(src.lastCounts().invalid, static_cast<std::size_t>(5 - k));
        EXPECT_EQ(src.lastLayout().fields.size(), 9u);
      }
      EXPECT_FALSE(src.next(s));
    }
}

TEST(Ros2Bag, SpanReadsTheFirstAndLastHeaderStamps) {
  TempDir d;
  const auto span = readRos2TrialSpan(writeBag(d.path).string(), "robot1/ouster/points", 'b');
  EXPECT_EQ(span.robot, 'b');
  EXPECT_EQ(span.first, 1700000000000000000ULL);
  EXPECT_EQ(span.last, 1700000000000000000ULL + 4 * 50000000ULL);
}

TEST(Ros2Bag, MissingTopicListsTheBagsTopics) {
  TempDir d;
  const fs::path folder = writeBag(d.path);
  const std::string e = errorOf([&] { Ros2ScanSource(folder.string(), "/os_cloud_node/points"); });
  EXPECT_NE(e.find("no topic /os_cloud_node/points"), std::string::npos) << e;
  EXPECT_NE(e.find("robot1/ouster/points (sensor_msgs/msg/PointCloud2)"), std::string::npos) << e;
  EXPECT_NE(e.find("robot1/ouster/imu"), std::string::npos) << e;
  const std::string wrong_type = errorOf([&] { Ros2ScanSource(folder.string(), "robot1/ouster/imu"); });
  EXPECT_NE(wrong_type.find("is not sensor_msgs/msg/PointCloud2"), std::string::npos) << wrong_type;
}

TEST(Ros2Bag, BadFilesAndFoldersAreClearErrors) {
  TempDir d;
  const fs::path junk = d.path / "junk.db3";
  std::ofstream(junk) << "this is not a database at all, just text\n";
  EXPECT_NE(errorOf([&] { Ros2BagReader(junk.string(), "t"); }).find(junk.string()), std::string::npos);
  const fs::path empty = d.path / "empty";
  fs::create_directories(empty);
  EXPECT_NE(errorOf([&] { Ros2BagReader(empty.string(), "t"); }).find("without .db3"), std::string::npos);
  EXPECT_NE(errorOf([&] { Ros2BagReader((d.path / "nothing").string(), "t"); }).find("no such"), std::string::npos);
  // An empty sqlite database (a 0-byte file): no rosbag2 tables.
  const fs::path other = d.path / "other.db3";
  std::ofstream{other};
  EXPECT_NE(errorOf([&] { Ros2BagReader(other.string(), "t"); }).find("not a ROS 2 bag"), std::string::npos);
  // A compressed bag.
  const fs::path folder = writeBag(d.path);
  std::ofstream(folder / "metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n  compression_format: zstd\n"
         "  relative_file_paths:\n    - robot1_x_lidar_0.db3\n";
  EXPECT_NE(errorOf([&] { Ros2BagReader(folder.string(), "t"); }).find("zstd"), std::string::npos);
}

TEST(Ros2Bag, TruncatedMessageInTheBagIsAClearError) {
  TempDir d;
  const fs::path folder = d.path / "cut";
  {
    Ros2BagWriter w(folder.string());
    const int t = w.addTopic("robot2/ouster/points", "sensor_msgs/msg/PointCloud2");
    auto cdr = encodeCdrPointCloud2(cloudAt(1700000000000000000ULL, 4));
    w.write(t, 1, cdr);
    cdr.resize(cdr.size() / 2);
    w.write(t, 2, cdr);
  }
  Ros2ScanSource src(folder.string(), "robot2/ouster/points");
  Scan s;
  ASSERT_TRUE(src.next(s));
  const std::string e = errorOf([&] { src.next(s); });
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  EXPECT_NE(e.find(folder.string() + " robot2/ouster/points"), std::string::npos) << e;
}

TEST(Ros2Bag, CuMultiBagWriterUsesTheRobotsTopic) {
  TempDir d;
  {
    CuMultiBagWriter w((d.path / "robot3_k_lidar").string(), 3);
    w.write(cloudAt(1700000000000000000ULL, 2));
  }
  const auto topics = listRos2Topics((d.path / "robot3_k_lidar").string());
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].name, "robot3/ouster/points");
}
