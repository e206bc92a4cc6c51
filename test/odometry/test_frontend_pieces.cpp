// Keyframer spacing, dewarping with a known motion, scan-line derivation, trajectory metrics, config reading.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cosmo/common/config.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/odometry/dewarp.hpp"
#include "cosmo/odometry/keyframer.hpp"
#include "cosmo/common/voxel_grid.hpp"
#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/odometry/scan_lines.hpp"
#include "cosmo/test_support/sim_scenes.hpp"
#include "cosmo/odometry/trajectory_metrics.hpp"

using namespace cosmo;

TEST(Keyframer, TwoMetreSpacingAndComposedOdometry) {
  odometry::Keyframer kf(2.0);
  std::vector<Pose3> poses;
  std::vector<std::size_t> kf_scans;
  std::vector<Pose3> rel;
  Pose3 T = makePose(1, 2, 3, 0, 0, 0.3);
  for (int i = 0; i < 40; ++i) {
    const auto d = kf.update(T);
    if (d.is_keyframe) {
      EXPECT_EQ(d.index, kf_scans.size());
      kf_scans.push_back(i);
      rel.push_back(d.relative);
    }
    poses.push_back(T);
    T = T * makePose(0.3, 0.0, 0.0, 0.0, 0.0, 0.01);  // 0.3 m per scan, turning
  }
  // 0.3 m steps: a keyframe once more than 2 m were travelled, i.e. every 7 scans.
  ASSERT_GE(kf_scans.size(), 5u);
  EXPECT_EQ(kf_scans[0], 0u);
  for (std::size_t k = 1; k < kf_scans.size(); ++k) {
    EXPECT_EQ(kf_scans[k] - kf_scans[k - 1], 7u);
    const Pose3 expected = poses[kf_scans[k - 1]].inverse() * poses[kf_scans[k]];
    EXPECT_LT(odometry::translationError(rel[k], expected), 1e-9);
    EXPECT_LT(odometry::rotationErrorRad(rel[k], expected), 1e-9);
  }
  EXPECT_TRUE(rel[0].isApprox(Pose3::Identity()));
}

TEST(Keyframer, StandingStillGivesNoKeyframes) {
  odometry::Keyframer kf;
  EXPECT_TRUE(kf.update(Pose3::Identity()).is_keyframe);
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(kf.update(makePose(0.001 * (i % 2), 0, 0, 0, 0, 0)).is_keyframe);
}

TEST(Dewarp, KnownConstantMotionRestoresTheStampFrame) {
  const sim::World scene = test_support::streetWorld(60.0, 8.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.beams = 16;
  lidar.columns = 256;
  // 10 m/s and 30 deg/s: a strongly distorted sweep.
  auto pose_at = [](double t) { return makePose(10.0 * t, 1.0 * t, 0.0, 0.0, 0.0, 0.5236 * t); };
  const double t_end = 0.3;
  const StampNs stamp = toStampNs(5.0);
  const Scan s = test_support::simulateSweep(scene, lidar, stamp, [&](double dt) { return pose_at(t_end + dt); });
  ASSERT_TRUE(s.hasTime());
  const Scan d = odometry::dewarp(s, [&](StampNs st) { return pose_at(t_end + (toSeconds(st) - 5.0)); });
  ASSERT_EQ(d.size(), s.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    // The same world point either way.
    const Eigen::Vector3d w_true = pose_at(t_end + s.time[i]) * s.points[i].cast<double>();
    const Eigen::Vector3d w_dewarped = pose_at(t_end) * d.points[i].cast<double>();
    worst = std::max(worst, (w_true - w_dewarped).norm());
    EXPECT_EQ(d.time[i], 0.0f);
  }
  EXPECT_LT(worst, 0.01);  // binning of the times (1/2048 of the sweep) and float storage
  // Without per-point times the scan is unchanged.
  Scan no_time = s;
  no_time.time.clear();
  EXPECT_EQ(odometry::dewarp(no_time, [](StampNs) { return Pose3::Identity(); }).points, no_time.points);
}

TEST(ScanLines, RingFieldElevationAndOrder) {
  const sim::World scene = test_support::streetWorld(60.0, 8.0);
  sim::LidarModel lidar = test_support::idealLidar();  // 64 x 1024
  Scan s = test_support::simulateSweep(scene, lidar, 1, [](double) { return Pose3::Identity(); });
  const odometry::LoamParams p;
  const odometry::ScanLines with_ring = organizeScanLines(s, p);
  EXPECT_EQ(with_ring.method, "ring");
  EXPECT_EQ(with_ring.lines.size(), 64u);
  // Drop the ring field and shuffle the points: lines from the elevation histogram.
  Scan shuffled = s;
  shuffled.ring.clear();
  std::vector<std::size_t> idx(s.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::mt19937_64 rng(1);
  std::shuffle(idx.begin(), idx.end(), rng);
  for (std::size_t i = 0; i < idx.size(); ++i) {
    shuffled.points[i] = s.points[idx[i]];
    shuffled.time[i] = s.time[idx[i]];
  }
  const odometry::ScanLines by_elev = organizeScanLines(shuffled, p);
  EXPECT_EQ(by_elev.method, "elevation");
  // The top beam sees little (sky) and may merge with its neighbour.
  EXPECT_GE(by_elev.lines.size(), 62u);
  EXPECT_LE(by_elev.lines.size(), 64u);
  EXPECT_EQ(by_elev.numPoints(), with_ring.numPoints());

  const auto dir = sharedPath("data/scan_snippets/kitti00");
  if (!dir) GTEST_SKIP() << "../shared/data/scan_snippets/kitti00 not found: KITTI part skipped";
  const odometry::ScanLines kitti = organizeScanLines(readScanFile(*dir + "/velodyne/000094.bin"), p);
  EXPECT_EQ(kitti.method, "order");
  EXPECT_GE(kitti.lines.size(), 60u);
  EXPECT_LE(kitti.lines.size(), 66u);
}

TEST(TrajectoryMetrics, UmeyamaAteAndSegments) {
  std::vector<Pose3> ref, est;
  const Pose3 A = makePose(3, -2, 1, 0.1, -0.2, 0.7);
  for (int i = 0; i < 300; ++i) {
    ref.push_back(makePose(0.5 * i, 5.0 * std::sin(0.02 * i), 0.0, 0.0, 0.0, 0.1 * std::cos(0.02 * i)));
    est.push_back(A * ref.back());
  }
  const odometry::AteResult ate = odometry::absoluteTrajectoryError(est, ref);
  EXPECT_LT(ate.rmse, 1e-9);
  EXPECT_TRUE(ate.alignment.isApprox(A.inverse(), 1e-9));
  for (const auto& e : odometry::segmentErrors(est, ref, {10.0, 50.0, 100.0})) {
    EXPECT_GT(e.count, 0u);
    EXPECT_LT(e.translation_percent, 1e-6);
  }
  // A 1 % scale error shows up as 1 % translation error.
  std::vector<Pose3> scaled = ref;
  for (auto& p : scaled) p.translation() *= 1.01;
  const auto seg = odometry::segmentErrors(scaled, ref, {100.0});
  EXPECT_NEAR(seg[0].translation_percent, 1.0, 0.05);
}

TEST(TrajectoryMetrics, ConstantVelocityFillsAreFound) {
  // A measured-looking trajectory (speed and turn rate varying every step, 0.5 mm of position noise), a stand of
  // 15 scans, and a gap (poses 30-41) filled by interpolating between poses 29 and 42: the position along the
  // line between them, the orientation at a constant rate.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.0005);
  std::vector<Pose3> poses{Pose3::Identity()};
  for (int i = 1; i < 120; ++i) {
    Pose3 step = makePose(0.8 + 0.05 * std::sin(0.7 * i), 0.01 * std::cos(1.3 * i), 0.0, 0.0, 0.0,
                          0.002 + 0.003 * std::sin(0.9 * i));
    if (i > 80 && i <= 95) step = Pose3::Identity();  // standing
    poses.push_back(poses.back() * step);
    poses.back().translation() += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  const Pose3 a = poses[29], b = poses[42];
  const Eigen::AngleAxisd turn(a.linear().transpose() * b.linear());
  for (int i = 30; i < 42; ++i) {
    const double s = (i - 29) / 13.0;
    poses[i].translation() = a.translation() + s * (b.translation() - a.translation());
    poses[i].linear() = a.linear() * Eigen::AngleAxisd(s * turn.angle(), turn.axis()).toRotationMatrix();
  }
  const auto runs = odometry::findConstantMotionRuns(poses);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].first, 29u);
  EXPECT_EQ(runs[0].last, 42u);
  EXPECT_NEAR(runs[0].step_m, (b.translation() - a.translation()).norm() / 13.0, 1e-6);
  // Shorter than the minimum: not reported.
  EXPECT_TRUE(odometry::findConstantMotionRuns(poses, 0.002, 0.005, 14).empty());
  // A simulated straight drive at a constant speed is one run end to end; an arc at a constant speed and turn
  // rate is not a fill (its steps turn with the vehicle).
  std::vector<Pose3> straight{Pose3::Identity()}, arc{Pose3::Identity()};
  for (int i = 1; i < 50; ++i) {
    straight.push_back(straight.back() * makePose(1.0, 0, 0, 0, 0, 0));
    arc.push_back(arc.back() * makePose(1.0, 0, 0, 0, 0, 0.01));
  }
  const auto all = odometry::findConstantMotionRuns(straight);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].first, 0u);
  EXPECT_EQ(all[0].last, 49u);
  EXPECT_TRUE(odometry::findConstantMotionRuns(arc).empty());
}

TEST(LoamParams, DefaultsAreThePaperValuesAndConfigOverrides) {
  const odometry::LoamParams d;
  EXPECT_EQ(d.neighbor_points, 3);
  EXPECT_EQ(d.number_sectors, 6);
  EXPECT_EQ(d.max_planar_feats_per_sector, 50);
  EXPECT_DOUBLE_EQ(d.edge_feat_threshold, 100.0);
  EXPECT_DOUBLE_EQ(d.max_avg_point_plane_dist, 0.2);
  const odometry::LoamParams c =
      odometry::LoamParams::fromConfig(ConfigNode::load(COSMO_SOURCE_DIR "/config/odometry.yaml"));
  EXPECT_EQ(c.max_icf_iterations, 20);
  EXPECT_DOUBLE_EQ(c.rotation_convergence_thresh, 1e-4);
  EXPECT_EQ(c.num_local_map_scans, 3);
}

TEST(VoxelFilter, KeepsTheFirstPointOfEachVoxel) {
  const std::vector<Eigen::Vector3d> pts{{0.05, 0.05, 0.05}, {0.15, 0.1, 0.0}, {0.25, 0.0, 0.0},
                                         {-0.05, 0.0, 0.0},  {0.31, 0.0, 0.0}, {std::nan(""), 0.0, 0.0}};
  EXPECT_EQ(voxelFilterIndices(pts, 0.2), (std::vector<std::uint32_t>{0, 2, 3}));
  EXPECT_EQ(voxelFilterIndices(pts, 0.0).size(), pts.size());
}
