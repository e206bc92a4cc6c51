// Simulated trials written in MCD's and CU-Multi's layouts (ros/trial_layout_writer.hpp, as cosmo_simulate
// --layout does) and read back through the trial readers (ros/bag_scan_source.hpp, trials/reference_file.hpp):
// containers chosen by content, invalid returns dropped, stamps, field types, and references whose
// body * extrinsic is the simulator's true LiDAR pose.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/ros/trial_layout_writer.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/trials/bag_format.hpp"
#include "cosmo/trials/cu_multi_layout.hpp"
#include "cosmo/trials/mcd_layout.hpp"
#include "cosmo/trials/reference_file.hpp"
#include "cosmo/trials/scan_cache.hpp"

#include "tiny_trial.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

constexpr int kBeams = 16, kColumns = 256, kScans = 22;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cosmo_layouts_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  /// The scan cache of compressed bags goes below the folder too.
  TempDir() {
    fs::create_directories(path);
    ::setenv("COSMO_SCAN_CACHE", (path / "scan_cache").c_str(), 1);
  }
  ~TempDir() { fs::remove_all(path); }
  std::vector<fs::path> cacheFiles() const {
    std::vector<fs::path> files;
    if (fs::exists(path / "scan_cache"))
      for (const auto& e : fs::directory_iterator(path / "scan_cache")) files.push_back(e.path());
    return files;
  }
};

sim::LidarModel smallLidar(double rate_hz) { return test::smallLidar(kBeams, kColumns, rate_hz); }
using test::tinyPlan;

/// Simulates the first kScans sweeps of the plan's trial and writes them in `layout`.
struct Fixture {
  sim::PlannedSequence plan;
  std::vector<Scan> truth;
  ros_glue::WrittenTrial written;
  Pose3 T_body_lidar;

  Fixture(ros_glue::TrialLayout layout, double rate_hz, const fs::path& dir) : plan(tinyPlan(smallLidar(rate_hz))) {
    const auto& t = plan.trials.at(0);
    T_body_lidar = t.params.extrinsicPose();
    sim::ScanSimulator simulator(*plan.world, smallLidar(rate_hz));
    ros_glue::LayoutTrialInfo info;
    info.name = t.params.name;
    info.robot_number = 2;
    info.platform = t.params.platform;
    info.beams = kBeams;
    info.columns = kColumns;
    info.rate_hz = rate_hz;
    auto writer = ros_glue::makeTrialLayoutWriter(layout, dir.string(), info);
    for (int k = 0; k < kScans; ++k) {
      truth.push_back(simulator.simulate(t.body, T_body_lidar, t.scan_stamps.at(k), t.noise_seed));
      writer->write(truth.back());
    }
    written = writer->finish(t.body, T_body_lidar);
  }
  Pose3 trueLidarPose(StampNs s) const { return plan.trials[0].body.atClamped(s) * T_body_lidar; }
};

sequence::TrialConfig trialOf(const ros_glue::WrittenTrial& w, const fs::path& dir, const std::string& topic) {
  sequence::TrialConfig c;
  c.robot = 'a';
  c.bag = (dir / w.bag).string();
  c.topic = topic;
  c.reference = (dir / w.reference).string();
  c.extrinsic = w.extrinsic;
  c.stamp_at_end = w.stamp_at_end;
  return c;
}

/// Reads every scan back and compares it with the simulated one.
void expectScansAsWritten(const Fixture& f, const sequence::TrialConfig& trial, const trials::OusterSweep& sweep,
                          const char* ring_type) {
  auto src = trials::openTrialScanSource(trial);
  EXPECT_EQ(src->size(), static_cast<std::size_t>(kScans));
  const double column = 1.0 / (kColumns * sweep.rate_hz);
  Scan s;
  for (const Scan& truth : f.truth) {
    ASSERT_TRUE(src->next(s));
    const auto& L = src->lastLayout();
    EXPECT_EQ(L.height, static_cast<std::uint32_t>(kBeams));
    EXPECT_EQ(L.width, static_cast<std::uint32_t>(kColumns));
    EXPECT_EQ(L.point_step, 48u);
    EXPECT_EQ(trials::pointTypeName(L.field("ring")->datatype), ring_type);
    EXPECT_EQ(trials::pointTypeName(L.field("t")->datatype), "uint32");
    EXPECT_EQ(L.field("range")->offset, 32u);
    EXPECT_EQ(src->lastCounts().points, static_cast<std::size_t>(kBeams * kColumns));
    EXPECT_EQ(src->lastCounts().invalid, kBeams * kColumns - truth.size());
    EXPECT_GT(src->lastCounts().invalid, 0u);
    // Stamped at the sweep end whatever the bag's convention (the header stamp, or a start stamp plus the
    // period), one column past the last column: each point keeps its true absolute time.
    const StampNs header = trials::ousterHeaderStamp(truth.stamp, sweep);
    if (sweep.stamp_at_end)
      EXPECT_EQ(s.stamp, header);
    else
      EXPECT_NEAR(static_cast<double>(s.stamp - header), 1e9 / sweep.rate_hz, 2.0);
    ASSERT_EQ(s.size(), truth.size());
    const double shift = static_cast<double>(static_cast<std::int64_t>(truth.stamp - s.stamp)) * 1e-9;
    EXPECT_NEAR(shift, -column, 2e-9);
    for (std::size_t i = 0; i < s.size(); ++i) {
      ASSERT_EQ(s.points[i], truth.points[i]) << i;
      ASSERT_EQ(s.ring[i], truth.ring[i]) << i;
      ASSERT_EQ(s.intensity[i], truth.intensity[i]) << i;
      ASSERT_NEAR(s.time[i], truth.time[i] + shift, 2e-7) << i;
    }
  }
  EXPECT_FALSE(src->next(s));
  const auto span = trials::readTrialSpan(trial);
  EXPECT_EQ(span.first, trials::ousterHeaderStamp(f.truth.front().stamp, sweep));
  EXPECT_EQ(span.last, trials::ousterHeaderStamp(f.truth.back().stamp, sweep));
}

}  // namespace

TEST(TrialLayouts, McdLayoutReadsBackAsSimulated) {
  TempDir d;
  const Fixture f(ros_glue::TrialLayout::Mcd, 10.0, d.path);
  EXPECT_EQ(f.written.bag, "walk_a/walk_a_os1_16.bag");
  EXPECT_EQ(f.written.topic, "/os_cloud_node/points");
  EXPECT_TRUE(f.written.stamp_at_end);
  const fs::path bag = d.path / f.written.bag;
  EXPECT_EQ(trials::detectBagFormat(bag.string()), trials::BagFormat::Ros1);
  EXPECT_NE(cosmo::readWholeFileOrEmpty(bag).find("compression=bz2"), std::string::npos);  // chunk headers
  const auto sweep = trials::mcdSweep(kBeams, kColumns, 10.0);
  // The first read decodes the bz2 bag and fills the scan cache; the second (other topic spelling) reads it.
  expectScansAsWritten(f, trialOf(f.written, d.path, "/os_cloud_node/points"), sweep, "uint8");
  EXPECT_EQ(d.cacheFiles().size(), 3u);  // the decoded scans, the trial's span and the entry's description
  expectScansAsWritten(f, trialOf(f.written, d.path, "os_cloud_node/points"), sweep, "uint8");

  // pose_inW.csv: body poses at the cloud stamps, row `num` 11 = cloud 10, ending 0.5 s before the last cloud.
  const fs::path ref = d.path / f.written.reference;
  EXPECT_EQ(trials::detectReferenceFormat(ref.string()), trials::ReferenceFormat::McdPoseCsv);
  const Trajectory body = trials::readReference(ref.string());
  ASSERT_EQ(body.size(), static_cast<std::size_t>(kScans - 10 - 5));
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(ref).substr(0, 27), "num,t,x,y,z,qx,qy,qz,qw\n11,");
  for (std::size_t i = 0; i < body.size(); ++i) {
    const StampNs s = trials::ousterHeaderStamp(f.truth[10 + i].stamp, sweep);
    EXPECT_NEAR(static_cast<double>(body.poses()[i].stamp), static_cast<double>(s), 500.0);
    const Pose3 lidar = body.poses()[i].pose * f.written.extrinsic;
    const Pose3 true_lidar = f.trueLidarPose(s);
    EXPECT_LT((lidar.translation() - true_lidar.translation()).norm(), 1e-6);
    EXPECT_LT(Eigen::AngleAxisd(lidar.linear().transpose() * true_lidar.linear()).angle(), 1e-8);
  }
  // A non-identity extrinsic, the handheld one, written to calibration.yaml as `body: os_sensor: T`.
  EXPECT_TRUE(f.written.extrinsic.isApprox(trials::mcdHandheldExtrinsic()));
  EXPECT_GT(Eigen::AngleAxisd(f.written.extrinsic.linear()).angle(), 3.0);
  const YAML::Node T = YAML::LoadFile((d.path / "walk_a" / "calibration.yaml").string())["body"]["os_sensor"]["T"];
  ASSERT_EQ(T.size(), 4u);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_DOUBLE_EQ(T[r][c].as<double>(), f.written.extrinsic.matrix()(r, c));

  // Missing topic: the ROS 1 reader lists the bag's topics.
  try {
    trials::openTrialScanSource(trialOf(f.written, d.path, "/velodyne_points"));
    FAIL() << "no error for a missing topic";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/os_cloud_node/points (sensor_msgs/PointCloud2)"), std::string::npos)
        << e.what();
  }
}

TEST(TrialLayouts, CuMultiLayoutReadsBackAsSimulated) {
  TempDir d;
  const Fixture f(ros_glue::TrialLayout::CuMulti, 20.0, d.path);
  EXPECT_EQ(f.written.bag, "robot2_walk_a_lidar");
  EXPECT_EQ(f.written.topic, "robot2/ouster/points");
  EXPECT_FALSE(f.written.stamp_at_end);
  const fs::path bag = d.path / f.written.bag;
  EXPECT_TRUE(fs::exists(bag / "metadata.yaml"));
  EXPECT_TRUE(fs::exists(bag / "robot2_walk_a_lidar_0.db3"));
  EXPECT_EQ(trials::detectBagFormat(bag.string()), trials::BagFormat::Ros2Sqlite);
  const auto sweep = trials::cuMultiSweep(kBeams, kColumns, 20.0);
  expectScansAsWritten(f, trialOf(f.written, d.path, "robot2/ouster/points"), sweep, "uint16");
  sequence::TrialConfig db3 = trialOf(f.written, d.path, "/robot2/ouster/points");
  db3.bag = (bag / "robot2_walk_a_lidar_0.db3").string();
  expectScansAsWritten(f, db3, sweep, "uint16");

  // Ground truth: one body pose per scan at its (start) stamp, in a UTM-offset frame.
  const fs::path ref = d.path / f.written.reference;
  EXPECT_EQ(trials::detectReferenceFormat(ref.string()), trials::ReferenceFormat::CuMultiCsv);
  const Trajectory body = trials::readReference(ref.string());
  ASSERT_EQ(body.size(), static_cast<std::size_t>(kScans));
  EXPECT_TRUE(f.written.extrinsic.isApprox(trials::cuMultiImuTLidar()));
  for (std::size_t i = 0; i < body.size(); ++i) {
    const StampNs s = trials::ousterHeaderStamp(f.truth[i].stamp, sweep);
    EXPECT_NEAR(static_cast<double>(body.poses()[i].stamp), static_cast<double>(s), 500.0);
    EXPECT_GT(body.poses()[i].pose.translation().y(), 4e6);
    Pose3 lidar = body.poses()[i].pose * f.written.extrinsic;
    lidar.translation() -= ros_glue::kSimulatedUtmOffset;
    const Pose3 true_lidar = f.trueLidarPose(s);
    EXPECT_LT((lidar.translation() - true_lidar.translation()).norm(), 1e-6);
    EXPECT_LT(Eigen::AngleAxisd(lidar.linear().transpose() * true_lidar.linear()).angle(), 1e-8);
  }
}

TEST(TrialLayouts, ContainerIsChosenByContentNotByName) {
  TempDir d;
  const Fixture mcd(ros_glue::TrialLayout::Mcd, 10.0, d.path / "mcd");
  const Fixture cu(ros_glue::TrialLayout::CuMulti, 20.0, d.path / "cu");
  // A ROS 1 bag named .db3 and a .db3 named .bag are still read as what they are.
  fs::copy_file(d.path / "mcd" / mcd.written.bag, d.path / "renamed.db3");
  fs::copy_file(d.path / "cu" / cu.written.bag / "robot2_walk_a_lidar_0.db3", d.path / "renamed.bag");
  EXPECT_EQ(trials::detectBagFormat((d.path / "renamed.db3").string()), trials::BagFormat::Ros1);
  EXPECT_EQ(trials::detectBagFormat((d.path / "renamed.bag").string()), trials::BagFormat::Ros2Sqlite);
  sequence::TrialConfig t = trialOf(cu.written, d.path / "cu", "robot2/ouster/points");
  t.bag = (d.path / "renamed.bag").string();
  auto src = trials::openTrialScanSource(t);
  Scan s;
  ASSERT_TRUE(src->next(s));
  EXPECT_EQ(s.size(), cu.truth[0].size());

  std::ofstream(d.path / "notes.bag") << "just some text\n";
  t.bag = (d.path / "notes.bag").string();
  try {
    trials::openTrialScanSource(t);
    FAIL() << "no error for a text file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(t.bag + ": neither a ROS 1 bag"), std::string::npos) << e.what();
  }
  t.bag = (d.path / "absent.bag").string();
  EXPECT_THROW(trials::readTrialSpan(t), std::runtime_error);
}

TEST(TrialLayouts, ScanCacheGivesBitIdenticalScansAndOnlyWhenComplete) {
  TempDir d;
  const Fixture f(ros_glue::TrialLayout::Mcd, 10.0, d.path);
  const sequence::TrialConfig trial = trialOf(f.written, d.path, "/os_cloud_node/points");
  auto readAll = [&](std::size_t limit) {
    std::vector<std::pair<Scan, trials::DecodeCounts>> out;
    auto src = trials::openTrialScanSource(trial);
    Scan s;
    while (out.size() < limit && src->next(s)) out.push_back({s, src->lastCounts()});
    return out;
  };
  // A run that stops early leaves no cache (nor a temporary file).
  EXPECT_EQ(readAll(3).size(), 3u);
  EXPECT_TRUE(d.cacheFiles().empty());
  const auto decoded = readAll(1000);
  ASSERT_EQ(d.cacheFiles().size(), 2u);  // the scans and the entry's description
  EXPECT_EQ(d.cacheFiles()[0].stem(), d.cacheFiles()[1].stem());
  EXPECT_TRUE(d.cacheFiles()[0].extension() == ".scans" || d.cacheFiles()[1].extension() == ".scans");
  const auto cached = readAll(1000);
  ASSERT_EQ(cached.size(), decoded.size());
  for (std::size_t k = 0; k < decoded.size(); ++k) {
    const Scan &a = decoded[k].first, &b = cached[k].first;
    ASSERT_EQ(a.stamp, b.stamp);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.time.size(), b.time.size());
    ASSERT_EQ(a.ring.size(), b.ring.size());
    ASSERT_EQ(a.intensity.size(), b.intensity.size());
    EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.size() * sizeof(a.points[0])), 0);
    EXPECT_EQ(std::memcmp(a.time.data(), b.time.data(), a.time.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(a.intensity.data(), b.intensity.data(), a.intensity.size() * sizeof(float)), 0);
    EXPECT_EQ(a.ring, b.ring);
    EXPECT_EQ(decoded[k].second.points, cached[k].second.points);
    EXPECT_EQ(decoded[k].second.invalid, cached[k].second.invalid);
  }
  // Disabled: nothing written; uncompressed and ROS 2 bags are never cached.
  fs::remove_all(d.path / "scan_cache");
  ::setenv("COSMO_SCAN_CACHE", "off", 1);
  EXPECT_EQ(readAll(1000).size(), decoded.size());
  EXPECT_TRUE(d.cacheFiles().empty());
  EXPECT_EQ(trials::scanCacheDir(), "");
}
