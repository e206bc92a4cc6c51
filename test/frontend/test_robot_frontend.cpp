// RobotFrontend on a tiny synthetic stream: keyframes every ~2 m, odometry chain, reference poses, and an
// inter-robot loop closure from a teammate's scan taken at the same place.
#include <gtest/gtest.h>

#include "cosmo/frontend/robot_frontend.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "../support/synthetic_team.hpp"

using namespace cosmo;
using namespace cosmo::frontend;
using namespace cosmo::sequence;

namespace {

FrontendParams testParams(OdometryKind odometry = OdometryKind::Loam) {
  FrontendParams p = FrontendParams::loadDir(defaultConfigDir());
  p.place.exclude_recent = 5;
  p.odometry = odometry;
  return p;
}

/// Every loop closure a step started, completed in order.
std::vector<LoopClosureAttempt> completed(RobotFrontend& f, const Step& step) {
  std::vector<LoopClosureAttempt> out;
  for (const auto& p : step.closures) out.push_back(f.complete(p));
  return out;
}

Trajectory sensorReference(const test::SyntheticTrial& t) {
  TrialTiming identity;
  identity.robot = t.robot;
  return toSensorReference(t.body, t.extrinsic, identity);
}

const std::vector<test::SyntheticTrial>& team() { return test::sharedSyntheticTeam(2, 60); }

}  // namespace

TEST(RobotFrontend, KeyframesEveryTwoMetresWithReferenceAndOdometryChain) {
  const auto& trial = team()[0];
  ASSERT_GT(trial.scans.size(), 20u);
  // Odometry from the reference: this tests the composition, not LOAM's accuracy.
  const Trajectory ref = sensorReference(trial);
  RobotFrontend fe('a', testParams(OdometryKind::Reference), ref);
  std::vector<KeyframeRecord> kfs;
  for (const auto& s : trial.scans) {
    const auto out = fe.add(OwnScan::of(s));
    if (out.keyframe) kfs.push_back(*out.keyframe);
  }
  ASSERT_GE(kfs.size(), 5u);
  EXPECT_EQ(kfs.front().index, 0u);
  EXPECT_EQ(kfs.front().stamp, trial.scans.front().stamp);
  Trajectory covered;
  for (const auto& p : ref.poses())
    if (p.stamp <= trial.scans.back().stamp) covered.append(p.stamp, p.pose);
  const double path = covered.length();
  EXPECT_NEAR(static_cast<double>(kfs.size()), path / 2.0, path / 2.0 * 0.35 + 2.0);
  Pose3 chained = kfs.front().odom_pose;
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    EXPECT_EQ(kfs[i].index, i);
    ASSERT_TRUE(kfs[i].reference.has_value());
    if (i > 0) {
      chained = chained * kfs[i].relative;
      EXPECT_LT((chained.translation() - kfs[i].odom_pose.translation()).norm(), 1e-6);
      const double step = kfs[i].relative.translation().norm();
      EXPECT_GT(step, 1.5);
      EXPECT_LT(step, 3.5);
    }
    const std::shared_ptr<const Scan> s = fe.keyframeScan(i);
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->stamp, kfs[i].stamp);
    EXPECT_GT(s->size(), 1000u);
    for (const auto& p : s->points) ASSERT_TRUE(p.allFinite());
  }
}

TEST(RobotFrontend, LoamOdometryRunsAndTakesKeyframeZeroAtTheFirstScan) {
  const auto& trial = team()[0];
  RobotFrontend fe('a', testParams(), sensorReference(trial));
  std::size_t kfs = 0;
  for (std::size_t i = 0; i < 20; ++i) {
    const auto out = fe.add(OwnScan::of(trial.scans[i]));
    if (out.keyframe) ++kfs;
    if (i == 0) {
      ASSERT_TRUE(out.keyframe.has_value());
      EXPECT_EQ(out.keyframe->index, 0u);
    }
    EXPECT_TRUE(out.odometry.pose.matrix().allFinite());
  }
  EXPECT_EQ(fe.scansProcessed(), 20u);
  EXPECT_EQ(fe.keyframes().size(), kfs);
}

TEST(RobotFrontend, TeammateScanAtTheSamePlaceGivesAnAcceptedInterRobotClosure) {
  const auto& a = team()[0];
  const auto& b = team()[1];
  RobotFrontend fa('a', testParams(OdometryKind::Reference), sensorReference(a));
  RobotFrontend fb('b', testParams(OdometryKind::Reference), sensorReference(b));
  // a few scans each: keyframe 0 of both robots at the shared start junction
  for (std::size_t i = 0; i < 5; ++i) {
    fa.add(OwnScan::of(a.scans[i]));
    fb.add(OwnScan::of(b.scans[i]));
  }
  ASSERT_NE(fa.keyframeScan(0), nullptr);
  const auto attempts = completed(fb, fb.add(TeammateScan::decoded('a', 0, *fa.keyframeScan(0), 123456789ULL)));
  ASSERT_FALSE(attempts.empty());
  const auto& lc = attempts.front();
  EXPECT_EQ(lc.owner, 'b');
  EXPECT_EQ(lc.robot1, 'b');
  EXPECT_EQ(lc.robot2, 'a');
  EXPECT_EQ(lc.index2, 0u);
  EXPECT_EQ(lc.computed_at, 123456789ULL);
  ASSERT_TRUE(lc.accepted) << lc.reason;
  const Pose3 truth = fb.keyframes()[lc.index1].reference->inverse() * *fa.keyframes()[0].reference;
  EXPECT_LT((truth.translation() - lc.measurement.translation()).norm(), 0.3);
  EXPECT_LT(rotationAngle(truth.inverse() * lc.measurement), 0.05);
  EXPECT_EQ(fb.teammateScansReceived(), 1u);
  EXPECT_THROW(fb.add(TeammateScan::decoded('b', 0, *fa.keyframeScan(0), 0)), std::invalid_argument);
}

TEST(RobotFrontend, ExternalOdometryAndDegenerateScansDoNotCrash) {
  RobotFrontend fe('a', testParams());
  Scan empty;
  empty.stamp = 1000;
  EXPECT_NO_THROW(fe.add(OwnScan::of(empty)));
  Scan nan_scan;
  nan_scan.stamp = 2000;
  nan_scan.points.assign(100, Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_NO_THROW(fe.add(OwnScan::of(nan_scan)));
  // external odometry: keyframes follow the given poses
  RobotFrontend ext('b', testParams(OdometryKind::External));
  std::size_t kfs = 0;
  for (int i = 0; i < 30; ++i) {
    Scan s;
    s.stamp = 1000000000ULL + i * 100000000ULL;
    s.points = {Eigen::Vector3f(5, 0, 0), Eigen::Vector3f(0, 5, 0)};
    Pose3 pose = Pose3::Identity();
    pose.translation() = Eigen::Vector3d(0.5 * i, 0, 0);
    ext.add(OdometryPose{s.stamp, pose});
    if (ext.add(OwnScan::of(s)).keyframe) ++kfs;
  }
  EXPECT_EQ(kfs, 6u);  // 0 at 0 m, then at 2.5, 5, 7.5, 10, 12.5 m (more than 2 m since the last)
  EXPECT_FALSE(ext.hasReference());
  EXPECT_FALSE(ext.keyframes().front().reference.has_value());
}

TEST(RobotFrontend, SharedFeatureCacheComputesADeliveredScanOnceWithTheSameResult) {
  const auto& a = team()[0];
  const auto& b = team()[1];
  // The same two robots twice: own caches, and one cache for both (as TeamRun runs them).
  const FrontendParams params = testParams(OdometryKind::Reference);
  RobotFrontend fa('a', params, sensorReference(a)), fb('b', params, sensorReference(b));
  auto shared = std::make_shared<FeatureCache>();
  const auto sharing = [&](const test::SyntheticTrial& t) {
    FrontendSetup setup{params, sensorReference(t)};
    setup.features = shared;
    return setup;
  };
  RobotFrontend sa('a', sharing(a)), sb('b', sharing(b));
  for (std::size_t i = 0; i < 5; ++i) {
    for (RobotFrontend* f : {&fa, &sa}) f->add(OwnScan::of(a.scans[i]));
    for (RobotFrontend* f : {&fb, &sb}) f->add(OwnScan::of(b.scans[i]));
  }
  // b registers a's keyframe 0 (the sender's own KeptScan, as TeamRun delivers it), then a registers b's keyframe 0
  const auto kept = [](RobotFrontend& from, char robot, StampNs at) {
    return TeammateScan::keptBySender(robot, 0, from.keptScan(0), at);
  };
  const auto own_ab = completed(fb, fb.add(kept(fa, 'a', 1000)));
  const auto own_ba = completed(fa, fa.add(kept(fb, 'b', 2000)));
  const auto sh_ab = completed(sb, sb.add(kept(sa, 'a', 1000)));
  const std::size_t after_first = shared->size();
  const auto sh_ba = completed(sa, sa.add(kept(sb, 'b', 2000)));
  ASSERT_FALSE(own_ab.empty());
  ASSERT_EQ(own_ab.size(), sh_ab.size());
  ASSERT_EQ(own_ba.size(), sh_ba.size());
  for (std::size_t i = 0; i < own_ab.size(); ++i) {
    EXPECT_EQ(own_ab[i].accepted, sh_ab[i].accepted);
    EXPECT_TRUE(own_ab[i].measurement.matrix() == sh_ab[i].measurement.matrix());  // bit for bit
  }
  for (std::size_t i = 0; i < own_ba.size(); ++i)
    EXPECT_TRUE(own_ba[i].measurement.matrix() == sh_ba[i].measurement.matrix());
  // b's pair put both keyframe-0 clouds in the cache; a's pair, over the same two scans, computed nothing new
  EXPECT_EQ(after_first, 2u);
  EXPECT_EQ(shared->size(), 2u);
  // a copied scan is another object: its own entry, never another scan's features
  const auto copy = completed(sb, sb.add(TeammateScan::decoded('a', 1, *sa.keyframeScan(0), 3000)));
  ASSERT_FALSE(copy.empty());
  EXPECT_EQ(shared->size(), 3u);
  EXPECT_TRUE(copy.front().measurement.matrix() == sh_ab.front().measurement.matrix());
}

TEST(RobotFrontend, ReferenceOdometryHoldsAWholeReferenceAndFallsBackToLoamPastAGrowingOne) {
  // A reference that ends at 1 s: a whole one is held at its end; one arriving pose by pose is held for
  // reference_tolerance_s (1 s) past it, then the scan takes LOAM and says so.
  FrontendParams params = testParams(OdometryKind::Reference);
  Trajectory ref;
  ref.append(0, Pose3::Identity());
  Pose3 end = Pose3::Identity();
  end.translation() = Eigen::Vector3d(1, 0, 0);
  ref.append(1000000000ULL, end);
  const auto scanAt = [](StampNs t) {
    Scan s;
    s.stamp = t;
    s.points = {Eigen::Vector3f(5, 0, 0), Eigen::Vector3f(0, 5, 0), Eigen::Vector3f(0, 0, 5)};
    return s;
  };
  RobotFrontend whole('a', FrontendSetup{params, ref, ReferenceArrival::Whole});
  FrontendSetup live_setup{params, {}, ReferenceArrival::PoseByPose};
  RobotFrontend live('a', live_setup);
  for (const auto& p : ref.poses()) EXPECT_TRUE(live.add(ReferencePose{p.stamp, p.pose}).notices.empty());
  EXPECT_FALSE(live.add(ReferencePose{500000000ULL, end}).notices.empty());  // not after the last: ignored
  for (StampNs t : {500000000ULL, 1500000000ULL, 5000000000ULL}) {
    const Step w = whole.add(OwnScan::of(scanAt(t)));
    EXPECT_TRUE(w.notices.empty()) << t;
    EXPECT_TRUE(w.odometry.pose.matrix() == ref.atClamped(t).matrix()) << t;
    const Step l = live.add(OwnScan::of(scanAt(t)));
    if (t <= 2000000000ULL) {
      EXPECT_TRUE(l.notices.empty()) << t;
      EXPECT_TRUE(l.odometry.pose.matrix() == ref.atClamped(t).matrix()) << t;
    } else {
      ASSERT_FALSE(l.notices.empty()) << t;  // (LOAM on three points may add its own)
      EXPECT_NE(l.notices.front().find("using LOAM"), std::string::npos);
      EXPECT_NE(l.odometry.initial_guess, "external");
    }
  }
}

TEST(RobotFrontend, DropsScansWithoutExternalOdometryOrWithStampsNotIncreasing) {
  FrontendSetup setup{testParams(OdometryKind::External)};
  setup.first_index = 7;  // a restarted front-end continues its robot's keyframe indices
  RobotFrontend fe('c', setup);
  Scan s;
  s.stamp = 1000000000ULL;
  s.points = {Eigen::Vector3f(5, 0, 0)};
  const Step none = fe.add(OwnScan::of(s));
  EXPECT_TRUE(none.dropped);
  ASSERT_EQ(none.notices.size(), 1u);
  EXPECT_NE(none.notices.front().find("no external odometry"), std::string::npos);
  EXPECT_EQ(fe.scansProcessed(), 0u);
  fe.add(OdometryPose{s.stamp, Pose3::Identity()});
  const Step first = fe.add(OwnScan::of(s));
  EXPECT_FALSE(first.dropped);
  ASSERT_TRUE(first.keyframe.has_value());
  EXPECT_EQ(first.keyframe->index, 7u);
  const Step again = fe.add(OwnScan::of(s));
  EXPECT_TRUE(again.dropped);
  EXPECT_EQ(fe.scansProcessed(), 1u);
  EXPECT_THROW(OdometrySource(parseOdometryKind("wheel"), ReferenceArrival::Whole, 0), std::invalid_argument);
}
