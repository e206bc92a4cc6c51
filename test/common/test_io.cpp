#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cosmo/common/config.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {
fs::path tempDir() {
  auto d = fs::temp_directory_path() / ("cosmo_test_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(ScanIo, PcdRoundTripAndBadBinSize) {
  const auto dir = tempDir();
  Scan s;
  for (int i = 0; i < 10; ++i) {
    s.points.emplace_back(i, 2.0f * i, -1.0f);
    s.intensity.push_back(static_cast<float>(i));
  }
  writePcd((dir / "a.pcd").string(), s);
  const Scan r = readScanFile((dir / "a.pcd").string());
  ASSERT_EQ(r.size(), 10u);
  EXPECT_FLOAT_EQ(r.points[3].y(), 6.0f);
  EXPECT_FLOAT_EQ(r.intensity[9], 9.0f);
  std::ofstream((dir / "bad.bin").string(), std::ios::binary) << "12345";
  try {
    readKittiBin((dir / "bad.bin").string());
    FAIL() << "expected a throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.bin"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(PoseIo, McdCsvRoundTripAndErrorsNameTheLine) {
  const auto dir = tempDir();
  Trajectory t;
  t.append(1666284719545345152ULL, makePose(1, 2, 3, 0.1, 0.2, 0.3));
  t.append(1666284719555345152ULL, makePose(1.1, 2, 3, 0.1, 0.2, 0.31));
  writeMcdPoseCsv((dir / "p.csv").string(), t);
  const Trajectory r = readMcdPoseCsv((dir / "p.csv").string());
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.poses()[1].stamp, t.poses()[1].stamp);
  EXPECT_LT((r.poses()[1].pose.matrix() - t.poses()[1].pose.matrix()).norm(), 1e-6);
  std::ofstream((dir / "bad.csv").string()) << "num,sec,x,y,z,qx,qy,qz,qw\n0,1.0,1,2,3,0,0,0\n";
  try {
    readMcdPoseCsv((dir / "bad.csv").string());
    FAIL() << "expected a throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(Config, WrongTypeNamesFileAndKey) {
  const auto dir = tempDir();
  std::ofstream((dir / "c.yaml").string()) << "odometry:\n  iterations: many\n  scale: 2.5\n";
  const auto c = ConfigNode::load((dir / "c.yaml").string());
  double scale = 1.0;
  c["odometry"].read("scale", scale);
  EXPECT_DOUBLE_EQ(scale, 2.5);
  int missing = 7;
  c["odometry"].read("absent", missing);
  EXPECT_EQ(missing, 7);
  int it = 0;
  try {
    c["odometry"].read("iterations", it);
    FAIL() << "expected a throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("c.yaml: odometry.iterations"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ConfigNode::load((dir / "none.yaml").string()), std::runtime_error);
  fs::remove_all(dir);
}

TEST(RealData, KittiScansAndPosesLoad) {
  const auto dir = sharedPath("data/scan_snippets/kitti00");
  if (!dir) GTEST_SKIP() << "../shared/data/scan_snippets/kitti00 not found: real-data check skipped";
  const Scan s = readScanFile(*dir + "/velodyne/000000.bin");
  EXPECT_GT(s.size(), 100000u);
  const auto cam = readKittiPoses(*dir + "/poses.txt");
  EXPECT_EQ(cam.size(), 4541u);
  const auto velo = kittiPosesToLidar(cam, readKittiCalibTr(*dir + "/calib.txt"));
  EXPECT_NEAR((velo[1].translation() - velo[0].translation()).norm(), 0.86, 0.02);
}
