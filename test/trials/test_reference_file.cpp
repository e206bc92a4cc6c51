// Reference files told apart by content (trials/reference_file.hpp): MCD pose_inW.csv, CU-Multi GT CSV, TUM,
// KITTI (+ times.txt); anything else rejected naming the file and line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cosmo/trials/cu_multi_layout.hpp"
#include "cosmo/trials/mcd_layout.hpp"
#include "cosmo/trials/reference_file.hpp"

using namespace cosmo;
using namespace cosmo::trials;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cosmo_reference_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

std::string errorOf(const std::string& path) {
  try {
    readReference(path);
  } catch (const std::runtime_error& e) { return e.what(); }
  return "";
}

std::vector<StampedPose> twoPoses(const Eigen::Vector3d& offset) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, -0.5, 1.0).normalized()));
  return {{1700000001100000000ULL, makePose(offset + Eigen::Vector3d(1.5, -2.25, 0.75), q)},
          {1700000001200000000ULL, makePose(offset + Eigen::Vector3d(1.75, -2.5, 0.8), q)}};
}

void expectPoses(const Trajectory& t, const std::vector<StampedPose>& truth, double tol) {
  ASSERT_EQ(t.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(t.poses()[i].stamp), static_cast<double>(truth[i].stamp), 1000.0);
    EXPECT_LT((t.poses()[i].pose.translation() - truth[i].pose.translation()).norm(), tol);
    EXPECT_TRUE(t.poses()[i].pose.linear().isApprox(truth[i].pose.linear(), 1e-9));
  }
}

}  // namespace

TEST(ReferenceFile, McdPoseInWIsDetectedAndRead) {
  TempDir d;
  const auto truth = twoPoses(Eigen::Vector3d::Zero());
  const std::string p = (d.path / "pose_inW.csv").string();
  writeMcdPoseCsv(p, truth, 11);
  std::ifstream in(p);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header, "num,t,x,y,z,qx,qy,qz,qw");
  EXPECT_EQ(first.rfind("11,1700000001.100000000,", 0), 0u) << first;
  EXPECT_EQ(detectReferenceFormat(p), ReferenceFormat::McdPoseCsv);
  expectPoses(readReference(p), truth, 1e-9);
}

TEST(ReferenceFile, CuMultiGroundTruthIsDetectedAndReadInUtm) {
  TempDir d;
  const auto truth = twoPoses(Eigen::Vector3d(4.8e5, 4.43e6, 1600.0));
  const std::string p = (d.path / "robot1_gt.csv").string();
  writeCuMultiGroundTruth(p, truth);
  std::ifstream in(p);
  std::string l1, l2;
  std::getline(in, l1);
  std::getline(in, l2);
  EXPECT_EQ(l1[0], '#');
  EXPECT_EQ(l2[0], '#');
  EXPECT_EQ(detectReferenceFormat(p), ReferenceFormat::CuMultiCsv);
  expectPoses(readReference(p), truth, 1e-6);
}

TEST(ReferenceFile, TumAndKittiAreDetectedAndRead) {
  TempDir d;
  const std::string tum = d.write("traj.txt",
                                  "# timestamp tx ty tz qx qy qz qw\n"
                                  "1700000000.5 1 2 3 0 0 0 1\n1700000000.6 1.5 2 3 0 0 0 1\n");
  EXPECT_EQ(detectReferenceFormat(tum), ReferenceFormat::Tum);
  const Trajectory t = readReference(tum);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.startStamp(), 1700000000500000000ULL);
  EXPECT_DOUBLE_EQ(t.poses()[1].pose.translation().x(), 1.5);

  const std::string kitti = d.write("poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 2 0 1 0 0 0 0 1 0\n");
  EXPECT_EQ(detectReferenceFormat(kitti), ReferenceFormat::Kitti);
  EXPECT_NE(errorOf(kitti).find("times.txt"), std::string::npos);
  d.write("times.txt", "0.0\n0.1\n");
  const Trajectory k = readReference(kitti);
  ASSERT_EQ(k.size(), 2u);
  EXPECT_EQ(k.endStamp(), 100000000ULL);
  EXPECT_DOUBLE_EQ(k.poses()[1].pose.translation().x(), 2.0);
}

TEST(ReferenceFile, GarbageIsRejectedNamingFileAndLine) {
  TempDir d;
  const std::string junk = d.write("junk.csv", "\n# a comment\nhello,world\n");
  const std::string e = errorOf(junk);
  EXPECT_NE(e.find(junk + ":3:"), std::string::npos) << e;
  EXPECT_NE(e.find("hello,world"), std::string::npos) << e;
  const std::string five = d.write("five.txt", "1 2 3 4 5\n");
  EXPECT_NE(errorOf(five).find(five + ":1:"), std::string::npos);
  const std::string empty = d.write("empty.csv", "");
  EXPECT_NE(errorOf(empty).find("no poses"), std::string::npos);
  EXPECT_NE(errorOf((d.path / "absent.csv").string()).find("cannot open"), std::string::npos);
  // Detected as MCD, a later line is bad: the reader names that line.
  const std::string bad_row = d.write("pose_inW.csv", "num,t,x,y,z,qx,qy,qz,qw\n11,1.0,0,0,0,0,0,0,1\n12,2.0,0,0\n");
  EXPECT_NE(errorOf(bad_row).find(bad_row + ":3:"), std::string::npos) << errorOf(bad_row);
  const std::string bad_cu = d.write("gt.csv", "# a\n# b\n1.0,0,0,0,0,0,0,1\n2.0,0,0,0,0,0,0,7\n");
  EXPECT_NE(errorOf(bad_cu).find(bad_cu + ":4:"), std::string::npos) << errorOf(bad_cu);
}
