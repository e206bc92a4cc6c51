// Simulated scans survive PointCloud2 conversion and a bag round trip (t, ring, intensity, stamp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "cosmo/trials/trial_scans.hpp"
#include "cosmo/common/pose_io.hpp"
#include "cosmo/ros/bag_io.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"

using namespace cosmo;
using namespace cosmo::sim;
namespace fs = std::filesystem;

namespace {
PlannedSequence tinyPlan() {
  SimulationParams p;
  p.world.blocks_x = 1;
  p.world.blocks_y = 1;
  p.world.outer_ring = 30;
  p.world.terrain_margin = 40;
  TrialParams t;
  t.name = "bag_a";
  t.motion = MotionParams::preset("atv");
  t.length = 40;
  t.start_node = 0;
  t.route.return_fraction = 1.0;
  p.trials.push_back(t);
  return planSequence(p);
}

void expectSame(const Scan& a, const Scan& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.stamp, b.stamp);
  ASSERT_TRUE(b.hasTime() && b.hasRing() && b.hasIntensity());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.points[i], b.points[i]) << i;
    ASSERT_EQ(a.ring[i], b.ring[i]) << i;
    ASSERT_EQ(a.intensity[i], b.intensity[i]) << i;
    ASSERT_NEAR(a.time[i], b.time[i], 1e-8) << i;  // t is whole ns, time a float
  }
}
}  // namespace

TEST(SimBag, PointCloud2KeepsTimeAndRing) {
  const auto seq = tinyPlan();
  const auto& t = seq.trials[0];
  ScanSimulator sim(*seq.world, LidarModel::os1_64());
  const Scan s = sim.simulate(t.body, t.params.extrinsicPose(), t.scan_stamps[5], 3);
  const auto msg = ros_glue::toPointCloud2(s, "os_sensor");
  EXPECT_EQ(msg.header.frame_id, "os_sensor");
  expectSame(s, ros_glue::fromPointCloud2(msg, true, "test"));
}

TEST(SimBag, BagRoundTrip) {
  const auto seq = tinyPlan();
  const auto& t = seq.trials[0];
  ScanSimulator sim(*seq.world, LidarModel::os1_64());
  const fs::path dir = fs::temp_directory_path() / ("cosmo_sim_bag_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string bag = (dir / "a.bag").string();
  std::vector<Scan> written;
  {
    ros_glue::ScanBagWriter w(bag);
    for (std::size_t k = 0; k < 5; ++k) {
      written.push_back(sim.simulate(t.body, t.params.extrinsicPose(), t.scan_stamps[k], 3));
      w.write("/os_cloud_node/points", written.back(), "os_sensor");
    }
  }
  trials::Ros1ScanSource r(bag, "/os_cloud_node/points");
  EXPECT_EQ(r.size(), 5u);
  Scan s;
  for (const auto& w : written) {
    ASSERT_TRUE(r.next(s));
    expectSame(w, s);
  }
  EXPECT_FALSE(r.next(s));
  // Ground truth CSV round trip.
  writeMcdPoseCsv((dir / "a_pose_inW.csv").string(), t.body);
  const Trajectory back = readMcdPoseCsv((dir / "a_pose_inW.csv").string());
  ASSERT_EQ(back.size(), t.body.size());
  EXPECT_EQ(back.startStamp(), t.body.startStamp());
  EXPECT_LT((back.poses().back().pose.translation() - t.body.poses().back().pose.translation()).norm(), 1e-5);
  fs::remove_all(dir);
}
