// End to end on simulated trials written in each real layout (MCD, CU-Multi, cosmo's own): the sequence config is
// read, the trial synchronized and run through the team pipeline (reference odometry: fast, and the groundtruth is
// what is checked), and every keyframe written must carry the simulator's true LiDAR pose as its groundtruth (1 mm,
// 0.01 deg: a wrong extrinsic, stamp convention or reference offset fails) and the dataset must be labelled. The
// same trial in each LiDAR's point layout (cosmo_simulate --points) gives the keyframes of its Ouster run, and a
// cloud without per-point times is run undewarped and says so.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <optional>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/ros/bag_io.hpp"
#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/ros/trial_layout_writer.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/sequence_planner.hpp"
#include "cosmo/trials/point_layouts.hpp"
#include "cosmo/trials/sequence_metadata.hpp"
#include "cosmo/trials/sequence_resolution.hpp"
#include "cosmo/trials/trial_reference.hpp"

#include "tiny_trial.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

constexpr int kBeams = 16, kColumns = 256;
constexpr double kSeconds = 7.0;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cosmo_layouts_e2e_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

using test::tinyPlan;

/// One simulated trial written in `layout` into `dir`, its sequence config beside it.
struct LayoutTrial {
  sim::PlannedSequence plan;
  Pose3 T_body_lidar;
  std::string config;

  /// `reference_span` (cosmo layout only): write the reference over [first, last] only, both included; `points`
  /// (cosmo layout only): the clouds' point layout, or none: Ouster's fields without `t`, no per-point time.
  LayoutTrial(ros_glue::TrialLayout layout, double rate_hz, const fs::path& dir,
              std::optional<std::pair<StampNs, StampNs>> reference_span = std::nullopt,
              std::optional<trials::PointLayout> points = trials::PointLayout::Ouster, int beams = kBeams,
              int columns = kColumns)
      : plan(tinyPlan(test::smallLidar(beams, columns, rate_hz))) {
    const auto& t = plan.trials.at(0);
    T_body_lidar = t.params.extrinsicPose();
    sim::ScanSimulator simulator(*plan.world, test::smallLidar(beams, columns, rate_hz));
    ros_glue::WrittenTrial w;
    std::unique_ptr<ros_glue::TrialLayoutWriter> writer;
    std::unique_ptr<ros_glue::ScanBagWriter> own;
    if (layout == ros_glue::TrialLayout::Cosmo) {
      own = std::make_unique<ros_glue::ScanBagWriter>((dir / "walk_a.bag").string());
      w = {"walk_a.bag", "/os_cloud_node/points", "walk_a_pose_inW.csv", T_body_lidar, true};
      Trajectory reference = t.body;
      if (reference_span) {
        std::vector<StampedPose> inside{{reference_span->first, t.body.atClamped(reference_span->first)}};
        for (const auto& p : t.body.poses())
          if (p.stamp > reference_span->first && p.stamp < reference_span->second) inside.push_back(p);
        inside.push_back({reference_span->second, t.body.atClamped(reference_span->second)});
        reference = Trajectory(std::move(inside));
      }
      writeMcdPoseCsv((dir / w.reference).string(), reference);
    } else {
      ros_glue::LayoutTrialInfo info;
      info.name = t.params.name;
      info.robot_number = 1;
      info.platform = t.params.platform;
      info.beams = beams;
      info.columns = columns;
      info.rate_hz = rate_hz;
      writer = ros_glue::makeTrialLayoutWriter(layout, dir.string(), info);
    }
    for (std::size_t k = 0; k < t.scan_stamps.size() && k < kSeconds * rate_hz; ++k) {
      Scan scan = simulator.simulate(t.body, T_body_lidar, t.scan_stamps[k], t.noise_seed);
      if (!points) scan.time.clear();
      if (own)
        own->write("/os_cloud_node/points", scan, "os_sensor", points.value_or(trials::PointLayout::Ouster));
      else
        writer->write(scan);
    }
    if (own)
      own->close();
    else
      w = writer->finish(t.body, T_body_lidar);
    config = (dir / "seq.yaml").string();
    std::ofstream out(config);
    out.precision(17);
    out << "name: e2e\nsource: synthetic\nseed: 3\nanchor: a\n";
    if (layout == ros_glue::TrialLayout::CuMulti) out << "reference_offset: anchor\n";
    out << "trials:\n  - robot: a\n    name: walk_a\n    bag: " << w.bag << "\n    topic: " << w.topic
        << "\n    stamp: " << (w.stamp_at_end ? "end" : "start") << "\n    reference: " << w.reference
        << "\n    extrinsic: [" << w.extrinsic.translation().x() << ", " << w.extrinsic.translation().y() << ", "
        << w.extrinsic.translation().z();
    const Eigen::Quaterniond q(w.extrinsic.linear());
    out << ", " << q.x() << ", " << q.y() << ", " << q.z() << ", " << q.w() << "]\n";
  }
  Pose3 trueLidarPose(StampNs s) const { return plan.trials[0].body.atClamped(s) * T_body_lidar; }
};

struct SequenceRun {
  std::vector<frontend::KeyframeRecord> keyframes;
  std::vector<std::shared_ptr<const Scan>> keyframe_scans;  ///< dewarped, as the dataset carries them
  sequence::SequenceTiming timing;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  bool labelled = false;
};

SequenceRun runSequence(const std::string& config_path,
                        frontend::OdometryKind odometry = frontend::OdometryKind::Reference) {
  const sequence::SequenceConfig config = sequence::SequenceConfig::load(config_path);
  SequenceRun r;
  r.timing = trials::synchronizeSequence(config);
  r.offset = trials::sequenceReferenceOffset(config);
  pipeline::TeamRunParams params;
  params.frontend.odometry = odometry;
  pipeline::TeamRun run("e2e", trials::loadSequenceReferences(config, r.timing), params, 1, r.timing.start());
  sequence::MergedScanStream stream = trials::openSequenceStream(config, r.timing);
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) run.add(robot, frontend::OwnScan::of(scan));
  run.finish(r.timing.end());
  dataset::BuildReport report;
  run.recorder().build(&report);
  r.labelled = report.labelled;
  r.keyframes = run.frontend('a').keyframes();
  for (std::size_t i = 0; i < r.keyframes.size(); ++i) r.keyframe_scans.push_back(run.frontend('a').keyframeScan(i));
  return r;
}

void expectTrueGroundtruth(const LayoutTrial& trial, const SequenceRun& r, const Eigen::Vector3d& frame_shift) {
  ASSERT_GE(r.keyframes.size(), 2u);
  EXPECT_TRUE(r.labelled);
  for (const auto& kf : r.keyframes) {
    ASSERT_TRUE(kf.reference.has_value()) << "keyframe " << kf.index;
    const Pose3 truth = trial.trueLidarPose(r.timing.of('a').toRecorded(kf.stamp));
    const Eigen::Vector3d expected = truth.translation() + frame_shift - r.offset;
    EXPECT_LT((kf.reference->translation() - expected).norm(), 1e-3) << "keyframe " << kf.index;
    const double deg = Eigen::AngleAxisd(truth.linear().transpose() * kf.reference->linear()).angle() * 180.0 / M_PI;
    EXPECT_LT(deg, 0.01) << "keyframe " << kf.index;
  }
}

}  // namespace

TEST(LayoutsEndToEnd, McdLayoutKeyframesCarryTheTrueLidarPose) {
  TempDir d;
  const LayoutTrial trial(ros_glue::TrialLayout::Mcd, 10.0, d.path);
  const SequenceRun r = runSequence(trial.config);
  expectTrueGroundtruth(trial, r, Eigen::Vector3d::Zero());
  // off until its first scan inside the reference (MCD's starts 1 s late)
  EXPECT_GE(toSeconds(r.timing.of('a').first - trial.plan.trials[0].scan_stamps.front()), 0.9);
}

TEST(LayoutsEndToEnd, CuMultiLayoutKeyframesCarryTheTrueLidarPose) {
  TempDir d;
  const LayoutTrial trial(ros_glue::TrialLayout::CuMulti, 20.0, d.path);
  const SequenceRun r = runSequence(trial.config);
  EXPECT_GT(r.offset.norm(), 4e6);  // the UTM-sized offset came off
  expectTrueGroundtruth(trial, r, ros_glue::kSimulatedUtmOffset);
}

TEST(LayoutsEndToEnd, CosmoLayoutKeyframesCarryTheTrueLidarPose) {
  TempDir d;
  const LayoutTrial trial(ros_glue::TrialLayout::Cosmo, 10.0, d.path);
  expectTrueGroundtruth(trial, runSequence(trial.config), Eigen::Vector3d::Zero());
}

// The same trial in MCD's layout and in cosmo's own gives the same keyframes, once both references cover the same
// scans: MCD's pose_inW.csv starts 1 s after the first scan (so that robot is off for its first 10 scans), so the
// cosmo-layout trial gets its reference over MCD's span. The MCD bag's organised clouds with invalid returns, its
// body-frame 10 Hz ground truth and its 180-degree extrinsic must then give the keyframes of the same scans (stamps
// within one column: MCD's is the sweep end) and the same groundtruth to 1 mm / 0.01 deg.
TEST(LayoutsEndToEnd, McdAndCosmoLayoutsOfOneTrialGiveTheSameKeyframes) {
  TempDir d;
  fs::create_directories(d.path / "mcd");
  fs::create_directories(d.path / "cosmo");
  const LayoutTrial mcd(ros_glue::TrialLayout::Mcd, 10.0, d.path / "mcd");
  const Trajectory mcd_body = readMcdPoseCsv((d.path / "mcd" / "walk_a" / "pose_inW.csv").string());
  const LayoutTrial own(ros_glue::TrialLayout::Cosmo, 10.0, d.path / "cosmo",
                        std::make_pair(mcd_body.startStamp(), mcd_body.endStamp()));
  const SequenceRun a = runSequence(mcd.config), b = runSequence(own.config);
  ASSERT_GE(a.keyframes.size(), 3u);
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  EXPECT_EQ(a.timing.of('a').first, b.timing.of('a').first);  // the same first covered scan
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    const auto& ka = a.keyframes[i];
    const auto& kb = b.keyframes[i];
    // the same scan: MCD's header stamp is the sweep end, one column after the simulator's last column's stamp
    const double column_ns = 1e9 / (10.0 * kColumns);
    const auto apart =
        static_cast<long long>(a.timing.of('a').toRecorded(ka.stamp) - b.timing.of('a').toRecorded(kb.stamp));
    EXPECT_LE(std::llabs(apart), static_cast<long long>(column_ns) + 1) << "keyframe " << i;
    ASSERT_TRUE(ka.reference && kb.reference) << "keyframe " << i;
    EXPECT_LT((ka.reference->translation() - kb.reference->translation()).norm(), 1e-3) << "keyframe " << i;
    const double deg =
        Eigen::AngleAxisd(ka.reference->linear().transpose() * kb.reference->linear()).angle() * 180.0 / M_PI;
    EXPECT_LT(deg, 0.01) << "keyframe " << i;
  }
}

namespace {

/// How far one run's keyframes lie from another's of the same trial: poses (the same keyframes: count and stamps)
/// and the points of their dewarped keyframe scans (point by point: the same points in the same order).
struct KeyframeGap {
  double pose_mm = 0.0, pose_deg = 0.0;
  double point_mm = 0.0;  ///< largest distance of one point
};

KeyframeGap keyframeGap(const SequenceRun& a, const SequenceRun& b, const std::string& layout) {
  KeyframeGap gap;
  EXPECT_EQ(a.keyframes.size(), b.keyframes.size()) << layout;
  for (std::size_t i = 0; i < std::min(a.keyframes.size(), b.keyframes.size()); ++i) {
    const Pose3 &pa = a.keyframes[i].odom_pose, &pb = b.keyframes[i].odom_pose;
    EXPECT_EQ(a.keyframes[i].stamp, b.keyframes[i].stamp) << layout << " keyframe " << i;
    gap.pose_mm = std::max(gap.pose_mm, (pa.translation() - pb.translation()).norm() * 1e3);
    gap.pose_deg =
        std::max(gap.pose_deg, Eigen::AngleAxisd(pa.linear().transpose() * pb.linear()).angle() * 180.0 / M_PI);
    const Scan &sa = *a.keyframe_scans[i], &sb = *b.keyframe_scans[i];
    EXPECT_EQ(sa.size(), sb.size()) << layout << " keyframe " << i;
    for (std::size_t k = 0; k < std::min(sa.size(), sb.size()); ++k)
      gap.point_mm = std::max(gap.point_mm, static_cast<double>((sa.points[k] - sb.points[k]).norm()) * 1e3);
  }
  return gap;
}

}  // namespace

// One simulated trial in each LiDAR's point layout (trials/point_layouts.hpp; livox-custom: a
// livox_ros_driver/CustomMsg bag), read back through the bag readers and run through the team pipeline, gives the
// keyframes of its Ouster run: the same stamps and poses (reference odometry: exactly), and the same dewarped
// keyframe scans within 1 mm per point. The layouts store the same points, and per-point times equal to within
// their time type's rounding: 1 ns for the integer ones and float32 s relative to the sweep, 256 ns for Livox's
// float64 absolute ns (its spacing at 1.7e18) — measured 0.00 mm for all but livox, 0.10 mm for livox. The sweep
// ends where the latest return is for the relative layouts (Ouster's `t`, Velodyne's `time`) and at the header
// stamp for the absolute ones, the same here. A reader that got a convention wrong (ns read as s, the sweep
// reversed, times dropped) moves points by decimetres to a metre: the undewarped run below measures 1,053 mm. (LOAM
// odometry is no yardstick at this size: on 16 x 256 beams it drifts metres over the walk, and times 1 ns apart
// already change its keyframes.)
TEST(LayoutsEndToEnd, EachPointLayoutGivesTheKeyframesOfOuster) {
  TempDir d;
  fs::create_directories(d.path / "ouster");
  const SequenceRun ouster = runSequence(LayoutTrial(ros_glue::TrialLayout::Cosmo, 10.0, d.path / "ouster").config);
  ASSERT_GE(ouster.keyframes.size(), 3u);
  for (trials::PointLayout layout :
       {trials::PointLayout::Velodyne, trials::PointLayout::Hesai, trials::PointLayout::Livox,
        trials::PointLayout::LivoxCustom, trials::PointLayout::SplitTime}) {
    const std::string name = trials::pointLayoutName(layout);
    fs::create_directories(d.path / name);
    const LayoutTrial trial(ros_glue::TrialLayout::Cosmo, 10.0, d.path / name, std::nullopt, layout);
    const SequenceRun run = runSequence(trial.config);
    const KeyframeGap gap = keyframeGap(ouster, run, name);
    std::printf("[ layout   ] %-12s %zu keyframes, gap to ouster: poses %.3f mm %.4f deg, points %.2f mm\n",
                name.c_str(), run.keyframes.size(), gap.pose_mm, gap.pose_deg, gap.point_mm);
    EXPECT_LT(gap.pose_mm, 1e-3) << name;
    EXPECT_LT(gap.pose_deg, 1e-4) << name;
    EXPECT_LT(gap.point_mm, 1.0) << name;
  }
}

// A cloud without per-point times is run undewarped, and says so once per trial: in the log of the sequence's
// resolution (cosmo_generate's and the player's) and in the dataset's metadata (`dewarp_a: off`). Its keyframe
// scans stray from the Ouster run's by decimetres (the size of a dewarping failure).
TEST(LayoutsEndToEnd, ACloudWithoutPointTimesRunsUndewarpedAndSaysSo) {
  TempDir d;
  fs::create_directories(d.path / "ouster");
  fs::create_directories(d.path / "none");
  const LayoutTrial ouster(ros_glue::TrialLayout::Cosmo, 10.0, d.path / "ouster");
  const LayoutTrial none(ros_glue::TrialLayout::Cosmo, 10.0, d.path / "none", std::nullopt, std::nullopt);
  const sequence::SequenceConfig config = sequence::SequenceConfig::load(none.config);
  const std::string off = trials::trialDewarpOff(config.trials.at(0));
  EXPECT_EQ(off,
            "its clouds carry no per-point time (fields x:float32@0 y:float32@4 z:float32@8 intensity:float32@12 "
            "ring:uint16@16): its sweeps are not dewarped");
  EXPECT_EQ(trials::trialDewarpOff(sequence::SequenceConfig::load(ouster.config).trials.at(0)), "");
  bool listed = false;
  for (const auto& [key, value] : trials::sequenceMetadata(config))
    if (key == "dewarp_a") listed = value == "off  # " + off;
  EXPECT_TRUE(listed);
  for (const auto& [key, value] : trials::sequenceMetadata(sequence::SequenceConfig::load(ouster.config)))
    EXPECT_NE(key, "dewarp_a");
  std::vector<std::string> said;
  trials::SequenceChoice choice;
  choice.sequence = none.config;
  choice.check = false;
  choice.estimate_trial = "walk_a";  // no noise models to load
  trials::resolveSequence(choice, trials::readTrialBases, [&](const std::string& line) { said.push_back(line); });
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "robot a (trial walk_a): " + off);

  const KeyframeGap gap = keyframeGap(runSequence(ouster.config), runSequence(none.config), "none");
  std::printf("[ layout   ] no time      gap to ouster: poses %.3f mm %.4f deg, points %.2f mm\n", gap.pose_mm,
              gap.pose_deg, gap.point_mm);
  EXPECT_GT(gap.point_mm, 50.0);
}
