// End to end on simulated trials written in each real layout (MCD, CU-Multi, cosmo's own): the sequence config is
// read, the trial synchronized and run through the team pipeline (reference odometry: fast, and the groundtruth is
// what is checked), and every keyframe written must carry the simulator's true LiDAR pose as its groundtruth (1 mm,
// 0.01 deg: a wrong extrinsic, stamp convention or reference offset fails) and the dataset must be labelled.
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

sim::LidarModel smallLidar(double rate_hz) { return test::smallLidar(kBeams, kColumns, rate_hz); }
using test::tinyPlan;

/// One simulated trial written in `layout` into `dir`, its sequence config beside it.
struct LayoutTrial {
  sim::PlannedSequence plan;
  Pose3 T_body_lidar;
  std::string config;

  /// `reference_span` (cosmo layout only): write the reference over [first, last] only, both included.
  LayoutTrial(ros_glue::TrialLayout layout, double rate_hz, const fs::path& dir,
              std::optional<std::pair<StampNs, StampNs>> reference_span = std::nullopt)
      : plan(tinyPlan(smallLidar(rate_hz))) {
    const auto& t = plan.trials.at(0);
    T_body_lidar = t.params.extrinsicPose();
    sim::ScanSimulator simulator(*plan.world, smallLidar(rate_hz));
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
      info.beams = kBeams;
      info.columns = kColumns;
      info.rate_hz = rate_hz;
      writer = ros_glue::makeTrialLayoutWriter(layout, dir.string(), info);
    }
    for (std::size_t k = 0; k < t.scan_stamps.size() && k < kSeconds * rate_hz; ++k) {
      const Scan scan = simulator.simulate(t.body, T_body_lidar, t.scan_stamps[k], t.noise_seed);
      if (own)
        own->write("/os_cloud_node/points", scan, "os_sensor");
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
  sequence::SequenceTiming timing;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  bool labelled = false;
};

SequenceRun runSequence(const std::string& config_path) {
  const sequence::SequenceConfig config = sequence::SequenceConfig::load(config_path);
  SequenceRun r;
  r.timing = trials::synchronizeSequence(config);
  r.offset = trials::sequenceReferenceOffset(config);
  pipeline::TeamRunParams params;
  params.frontend.odometry = frontend::OdometryKind::Reference;
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
