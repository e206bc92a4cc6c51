// LOAM odometry: real scan pairs against ground truth, a synthetic trial with motion distortion, degenerate input.
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/test_support/sim_scenes.hpp"
#include "cosmo/odometry/trajectory_metrics.hpp"

using namespace cosmo;

namespace {
constexpr double kRadToDeg = 180.0 / M_PI;

/// Relative pose estimated by a fresh odometry from scan a to scan b.
Pose3 odometryStep(Scan a, Scan b) {
  a.stamp = toStampNs(1.0);
  b.stamp = toStampNs(1.1);
  odometry::LoamOdometry odom;
  odom.update(a);
  const odometry::OdometryResult r = odom.update(b);
  EXPECT_TRUE(r.ok) << r.warning;
  return r.pose;
}

std::string kittiScan(const std::string& dir, int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "/velodyne/%06d.bin", frame);
  return dir + name;
}
/// Runs LOAM over n distorted sweeps (10 Hz, sweep k ends at 0.1 k s) of a sensor moving along pose_at; every
/// scan must be accepted. est / gt are the estimated and true poses relative to the first scan.
template <class PoseAt>
void runDistortedSweeps(const sim::World& scene, const sim::LidarModel& lidar, std::uint64_t noise_seed,
                        const PoseAt& pose_at, int n, std::vector<Pose3>& est, std::vector<Pose3>& gt,
                        const odometry::LoamParams& params = odometry::LoamParams{}) {
  odometry::LoamOdometry odom(params);
  for (int k = 0; k < n; ++k) {
    const double t_end = 0.1 * k;
    const Scan s = test_support::simulateSweep(
        scene, lidar, toStampNs(1.0 + t_end), [&](double dt) { return pose_at(t_end + dt); }, noise_seed);
    const odometry::OdometryResult r = odom.update(s);
    EXPECT_TRUE(r.ok) << "scan " << k << ": " << r.warning;
    est.push_back(r.pose);
    gt.push_back(pose_at(0.0).inverse() * pose_at(t_end));
  }
}

}  // namespace

TEST(LoamRealScans, KittiConsecutiveFramesWithinTargets) {
  const auto dir = sharedPath("data/scan_snippets/kitti00");
  if (!dir) GTEST_SKIP() << "../shared/data/scan_snippets/kitti00 not found (set COSMO_SHARED_DIR)";
  const auto ref = kittiPosesToLidar(readKittiPoses(*dir + "/poses.txt"), readKittiCalibTr(*dir + "/calib.txt"));
  // Frames 94->95 and 198->199 (0.47 m and 0.52 m). Frames 0->1->2 are reported by bench_odometry but not tested:
  // poses.txt repeats one step there (a constant-velocity fill over frames 0-13, see the README).
  const auto fills = odometry::findConstantMotionRuns(ref);
  ASSERT_FALSE(fills.empty());
  EXPECT_EQ(fills.front().first, 0u);
  EXPECT_GE(fills.front().last, 2u);
  for (const auto& f : fills) EXPECT_TRUE(f.last < 94 || f.first > 199) << f.first << "-" << f.last;
  for (int f : {94, 198}) {
    const Pose3 est = odometryStep(readScanFile(kittiScan(*dir, f)), readScanFile(kittiScan(*dir, f + 1)));
    const Pose3 gt = ref[f].inverse() * ref[f + 1];
    EXPECT_LT(odometry::translationError(est, gt), 0.05) << "frame " << f;
    EXPECT_LT(odometry::rotationErrorRad(est, gt) * kRadToDeg, 0.2) << "frame " << f;
  }
}

TEST(LoamRealScans, Hdl32PairMatchesExpectedTransform) {
  const auto dir = sharedPath("data/scan_snippets/hdl32_pair");
  if (!dir) GTEST_SKIP() << "../shared/data/scan_snippets/hdl32_pair not found (set COSMO_SHARED_DIR)";
  // Unordered PCD without ring: lines come from the elevation histogram.
  const Pose3 est = odometryStep(readScanFile(*dir + "/251370668.pcd"), readScanFile(*dir + "/251371071.pcd"));
  const Pose3 gt = readMatrixPose(*dir + "/relative.txt");
  EXPECT_LT(odometry::translationError(est, gt), 0.03);
  EXPECT_LT(odometry::rotationErrorRad(est, gt) * kRadToDeg, 0.2);
}

TEST(LoamSynthetic, DrivingWithMotionDistortionRecoversMotion) {
  // 64 x 1024 sweeps in a ray-cast street, 8 m/s with a slow turn, every sweep distorted by its own motion.
  const sim::World scene = test_support::streetWorld(120.0, 8.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.range_sigma = 0.01;
  const std::uint64_t seed = 42;
  auto pose_at = [](double t) { return makePose(8.0 * t, 0.5 * std::sin(0.5 * t), 0.0, 0.0, 0.0, 0.1 * t); };
  std::vector<Pose3> est, gt;
  const int n = 12;
  runDistortedSweeps(scene, lidar, seed, pose_at, n, est, gt);
  for (int k = 1; k < n; ++k) {
    const Pose3 de = est[k - 1].inverse() * est[k], dg = gt[k - 1].inverse() * gt[k];
    EXPECT_LT(odometry::translationError(de, dg), 0.02) << "step " << k;
    EXPECT_LT(odometry::rotationErrorRad(de, dg) * kRadToDeg, 0.1) << "step " << k;
  }
  // End-point drift over ~9 m below 1 %.
  EXPECT_LT(odometry::translationError(est.back(), gt.back()) / gt.back().translation().norm(), 0.01);
}

TEST(LoamDegenerate, NeverThrowsAndFallsBackToTheMotionModel) {
  const sim::World scene = test_support::streetWorld(60.0, 8.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.beams = 32;
  lidar.columns = 512;
  auto pose_at = [](double t) { return makePose(5.0 * t, 0.0, 0.0, 0.0, 0.0, 0.0); };
  odometry::LoamOdometry odom;
  StampNs stamp = toStampNs(1.0);
  auto sweep = [&](double t) {
    Scan s = test_support::simulateSweep(scene, lidar, stamp, [&](double dt) { return pose_at(t + dt); });
    s.time.clear();
    return s;
  };
  EXPECT_TRUE(odom.update(sweep(0.0)).ok);
  stamp += toStampNs(0.1);
  const odometry::OdometryResult good = odom.update(sweep(0.1));
  EXPECT_TRUE(good.ok) << good.warning;
  EXPECT_NEAR(good.delta.translation().x(), 0.5, 0.05);

  // Empty scan.
  Scan empty;
  stamp += toStampNs(0.1);
  empty.stamp = stamp;
  odometry::OdometryResult r = odom.update(empty);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.warning.empty());
  EXPECT_NEAR(r.delta.translation().x(), 0.5, 0.05) << "motion model continues the last motion";
  // All-NaN scan and a scan of 50 points.
  Scan nan_scan;
  stamp += toStampNs(0.1);
  nan_scan.stamp = stamp;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < 5000; ++i) nan_scan.points.emplace_back(nan, 1.0f, nan);
  r = odom.update(nan_scan);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.pose.matrix().allFinite());
  Scan few = sweep(0.4);
  few.points.resize(50);
  few.intensity.resize(50);
  few.ring.resize(50);
  stamp += toStampNs(0.1);
  few.stamp = stamp;
  r = odom.update(few);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.pose.matrix().allFinite());
  // Back to normal scans: the odometry carries on.
  stamp += toStampNs(0.1);
  r = odom.update(sweep(0.5));
  EXPECT_TRUE(r.pose.matrix().allFinite());
  EXPECT_NEAR(r.pose.translation().x(), 2.5, 0.3);
}

TEST(LoamDegenerate, FeaturelessCorridorKeepsTheMotionModelAlongTheAxis) {
  // Two walls, floor and ceiling, nothing else: translation along x is unobservable.
  const sim::World scene = test_support::corridorWorld();
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.beams = 32;
  lidar.columns = 512;
  lidar.fov_up_deg = 30.0;
  lidar.fov_down_deg = -30.0;
  auto pose_at = [](double t) { return makePose(1.0 * t, 0.0, 0.0, 0.0, 0.0, 0.0); };
  odometry::LoamOdometry odom;
  bool warned = false;
  odometry::OdometryResult r;
  for (int k = 0; k < 6; ++k) {
    Scan s = test_support::simulateSweep(scene, lidar, toStampNs(1.0 + 0.1 * k),
                                         [&](double dt) { return pose_at(0.1 * k + dt); });
    s.time.clear();
    ASSERT_NO_THROW(r = odom.update(s));
    EXPECT_TRUE(r.pose.matrix().allFinite());
    if (!r.ok) warned = true;
  }
  EXPECT_TRUE(warned) << "a corridor should be reported as degenerate";
  // Lateral and vertical position stay well determined.
  EXPECT_NEAR(r.pose.translation().y(), 0.0, 0.05);
  EXPECT_NEAR(r.pose.translation().z(), 0.0, 0.05);
}

TEST(LoamSynthetic, AcceleratingTrialDoesNotOscillate) {
  // Regression (default demo trial a, 481 m ATV): features deskewed with the scan's own estimate, iterated to
  // self-consistency, made the scan-to-scan motion oscillate with period 2 and a growing amplitude while the
  // vehicle accelerated (steps of 0.1 / 0.3 m alternating, then metres, "degenerate geometry" warnings and
  // ~45 % too long a path). Here: a start from rest, 2 m/s^2 up to 6 m/s, with a gentle weave.
  const sim::World scene = test_support::streetWorld(200.0, 8.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.range_sigma = 0.02;
  const std::uint64_t seed = 7;
  auto x_at = [](double t) { return t < 1.0 ? 0.0 : 0.5 * 0.8 * (t - 1.0) * (t - 1.0); };
  auto pose_at = [&](double t) {
    return makePose(x_at(t), 0.3 * std::sin(0.4 * t), 0.0, 0.0, 0.0, 0.03 * std::sin(0.6 * t));
  };
  std::vector<Pose3> est, gt;
  const int n = 50;
  runDistortedSweeps(scene, lidar, seed, pose_at, n, est, gt);
  double len_est = 0.0, len_gt = 0.0;
  for (int k = 1; k < n; ++k) {
    const Pose3 de = est[k - 1].inverse() * est[k], dg = gt[k - 1].inverse() * gt[k];
    EXPECT_LT(odometry::translationError(de, dg), 0.03)
        << "step " << k << ": " << de.translation().norm() << " m vs " << dg.translation().norm() << " m";
    len_est += de.translation().norm();
    len_gt += dg.translation().norm();
  }
  // The keyframer spaces keyframes by odometry path length: it must match the true one.
  EXPECT_NEAR(len_est / len_gt, 1.0, 0.02) << len_est << " m vs " << len_gt << " m";
  EXPECT_LT(odometry::translationError(est.back(), gt.back()) / len_gt, 0.02);
}

TEST(LoamSynthetic, WalkingSwayIsDeskewed) {
  // A walker at 1.4 m/s with a 3 cm bob and +-1.1 deg roll / pitch sway (0.9 / 1.8 Hz): about 1 deg of tilt
  // change within one sweep, reversing every few scans. Deskewing only x / y / yaw, or with the previous
  // scan's motion only, left ~0.07 deg/m over 10 m here (0.023 with the 6-DoF re-deskew, 0.015 with the
  // continuous-time rotation).
  const sim::World scene = test_support::streetWorld(80.0, 9.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.range_sigma = 0.01;
  const std::uint64_t seed = 5;
  auto pose_at = [](double t) {
    return makePose(1.4 * t, 0.0, 0.03 * std::sin(2 * M_PI * 1.8 * t), 0.02 * std::sin(2 * M_PI * 0.9 * t),
                    0.02 * std::sin(2 * M_PI * 1.8 * t + 0.5), 0.0);
  };
  std::vector<Pose3> est, gt;
  runDistortedSweeps(scene, lidar, seed, pose_at, 150, est, gt);
  const auto seg = odometry::segmentErrors(est, gt, {10.0}, 1);
  ASSERT_GT(seg[0].count, 50u);
  EXPECT_LT(seg[0].translation_percent, 1.0);
  EXPECT_LT(seg[0].rotation_deg_per_m, 0.04);
  // The rotation over each sweep estimated with the pose (deskew_rotation_tie, the default) against the
  // re-deskew with the estimate it replaced.
  odometry::LoamParams redeskew;
  redeskew.deskew_rotation_tie = 0.0;
  std::vector<Pose3> est2, gt2;
  runDistortedSweeps(scene, lidar, seed, pose_at, 150, est2, gt2, redeskew);
  const auto seg2 = odometry::segmentErrors(est2, gt2, {10.0}, 1);
  std::printf("walking sway, 10 m: %.4f deg/m (continuous-time rotation), %.4f deg/m (re-deskew)\n",
              seg[0].rotation_deg_per_m, seg2[0].rotation_deg_per_m);
  EXPECT_LT(seg[0].rotation_deg_per_m, 0.8 * seg2[0].rotation_deg_per_m);
}

TEST(LoamSynthetic, MapInsertGateKeepsAStandingStartRegistered) {
  // A sensor standing 1 s, then walking off (1.4 m/s^2 for 1 s, then 1.4 m/s). With map_insert_min_translation /
  // _rotation_deg the standing scans stay out of the local map (no copies of one scan) and the walk-off must still
  // be registered step by step. (This street does not reproduce ci_c's 30 cm / 4.35 deg standing-start jump: the
  // test passes without the gate too, with or without range noise; it guards the gate, not the fix.)
  const sim::World scene = test_support::streetWorld(60.0, 8.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.range_sigma = 0.01;
  const std::uint64_t seed = 3;
  auto x_at = [](double t) { return t < 1.0 ? 0.0 : t < 2.0 ? 0.7 * (t - 1.0) * (t - 1.0) : 0.7 + 1.4 * (t - 2.0); };
  auto pose_at = [&](double t) { return makePose(x_at(t), 0.0, 0.0, 0.0, 0.0, 0.0); };
  odometry::LoamParams params;
  params.map_insert_min_translation = 0.02;
  params.map_insert_min_rotation_deg = 0.2;
  odometry::LoamOdometry odom(params);
  Pose3 prev = Pose3::Identity();
  for (int k = 0; k < 25; ++k) {
    const double t_end = 0.1 * k;
    const Scan s = test_support::simulateSweep(
        scene, lidar, toStampNs(1.0 + t_end), [&](double dt) { return pose_at(t_end + dt); }, seed);
    const odometry::OdometryResult r = odom.update(s);
    EXPECT_TRUE(r.ok) << "scan " << k << ": " << r.warning;
    const Pose3 gt_step = pose_at(t_end - 0.1).inverse() * pose_at(t_end);
    const Pose3 step = prev.inverse() * r.pose;
    if (k > 0) {
      EXPECT_LT(odometry::translationError(step, gt_step), 0.03) << "step " << k;
      EXPECT_LT(odometry::rotationErrorRad(step, gt_step) * kRadToDeg, 0.2) << "step " << k;
    }
    prev = r.pose;
  }
}
