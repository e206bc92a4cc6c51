// Which scans of a trial the pipeline uses (sequence/trial_coverage.hpp): the robot is off until its first scan
// inside its reference, stops after its last, and a run fails on a reference gap; 10 / 20 Hz references
// interpolated to keyframe and point times. Also the dewarp and the constant-velocity deskew on start-stamped
// sweeps (test/trials/test_stamp_convention.cpp has the decode of both conventions).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "cosmo/odometry/dewarp.hpp"
#include "cosmo/test_support/sim_scenes.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/trial_coverage.hpp"

using namespace cosmo;
using namespace cosmo::sequence;

namespace {

constexpr double kT0 = 1.7e9;  // recorded time of the first sweep end, s

/// Sensor pose in the world at time t (s after kT0): 8 m/s along a gentle left curve with a little pitch sway.
Pose3 truePose(double t) {
  Pose3 p = Pose3::Identity();
  const double yaw = 0.15 * t;
  p.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.01 * std::sin(3.0 * t), Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  p.translation() = Eigen::Vector3d(8.0 * t, 0.6 * t * t, 0.0);
  return p;
}

sim::LidarModel smallLidar() {
  sim::LidarModel l = test_support::idealLidar();
  l.beams = 16;
  l.columns = 512;
  return l;
}

/// n sweeps of 0.1 s stamped at their end (the latest point at time 0), sweep k ending at kT0 + 0.1 k.
std::vector<Scan> endStamped(int n) {
  static const sim::World scene = test_support::streetWorld(300.0);
  std::vector<Scan> scans;
  for (int k = 0; k < n; ++k) {
    const double t_end = 0.1 * k;
    scans.push_back(test_support::simulateSweep(scene, smallLidar(), toStampNs(kT0 + t_end),
                                                [&](double dt) { return truePose(t_end + dt); }));
  }
  return scans;
}

/// The same sweeps stamped at their first point, point times >= 0 (as a start-stamped reader decodes them).
std::vector<Scan> startStamped(std::vector<Scan> scans) {
  for (Scan& s : scans) {
    float earliest = 0.0f;
    for (float t : s.time) earliest = std::min(earliest, t);
    s.stamp -= static_cast<StampNs>(std::llround(-static_cast<double>(earliest) * 1e9));
    for (float& t : s.time) t -= earliest;
  }
  return scans;
}

/// A 10 Hz reference (poses at the sweep ends) from `from` to `to` seconds after kT0.
Trajectory reference(double from, double to, double rate = 10.0) {
  std::vector<StampedPose> poses;
  for (double t = from; t <= to + 1e-9; t += 1.0 / rate) poses.push_back({toStampNs(kT0 + t), truePose(t)});
  return Trajectory(std::move(poses));
}

std::vector<Scan> drain(ScanSource& source) {
  std::vector<Scan> out;
  Scan s;
  while (source.next(s)) out.push_back(s);
  return out;
}

double angleDeg(const Pose3& a, const Pose3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

}  // namespace

TEST(StampConvention, DewarpPutsBothCopiesOnTheSameWorldPoints) {
  const auto end = endStamped(2);
  const auto start = startStamped(end);
  auto pose_at = [](StampNs t) { return truePose(toSeconds(t) - kT0); };
  for (std::size_t k = 0; k < end.size(); ++k) {
    const Scan de = odometry::dewarp(end[k], pose_at), ds = odometry::dewarp(start[k], pose_at);
    const Pose3 te = pose_at(end[k].stamp), ts = pose_at(start[k].stamp);
    ASSERT_EQ(de.size(), ds.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < de.size(); ++i)
      worst = std::max(worst, (te * de.points[i].cast<double>() - ts * ds.points[i].cast<double>()).norm());
    EXPECT_LT(worst, 1e-3) << "scan " << k;
    // and the dewarp is right: a point of the end copy at the true world position
    double truth_err = 0.0;
    for (std::size_t i = 0; i < de.size(); i += 97) {
      const Pose3 at_point =
          pose_at(end[k].stamp - static_cast<StampNs>(std::llround(-static_cast<double>(end[k].time[i]) * 1e9)));
      truth_err =
          std::max(truth_err, (te * de.points[i].cast<double>() - at_point * end[k].points[i].cast<double>()).norm());
    }
    EXPECT_LT(truth_err, 1e-3);
  }
}

TEST(StampConvention, ConstantVelocityDeskewCoversStartStampedSweeps) {
  // delta = the motion over the last period; a point at +0.08 s (a start-stamped sweep) moves 0.8 of it forward
  Pose3 delta = Pose3::Identity();
  delta.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  const std::vector<Eigen::Vector3d> pts{Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(5, 0, 0)};
  const std::vector<float> times{0.08f, -0.08f};
  std::vector<Eigen::Vector3d> out;
  odometry::deskewConstantVelocity(pts, times, delta, 0.1, out);
  EXPECT_NEAR(out[0].x(), 5.8, 0.01);
  EXPECT_NEAR(out[1].x(), 4.2, 0.01);
}

TEST(ReferenceSpan, RobotIsOffUntilItsFirstCoveredScanAndStopsAfterTheLast) {
  // MCD-like: 10 Hz reference starting 1.0 s after the first sweep end, ending 0.5 s before the last
  const auto scans = endStamped(40);  // sweep ends at 0.0 .. 3.9 s
  TrialCoverage coverage("ntu_day_01", reference(1.0, 3.4));
  CoveredScanSource source(std::make_unique<VectorScanSource>(scans), coverage);
  const auto used = drain(source);
  ASSERT_FALSE(used.empty());
  // sweep 10 ends at 1.0 s but starts before it: the first covered sweep is 11 (its first point after 1.0 s)
  EXPECT_EQ(used.front().stamp, scans[11].stamp);
  EXPECT_EQ(used.back().stamp, scans[34].stamp);
  EXPECT_EQ(used.size(), 24u);
  EXPECT_EQ(source.skippedBefore(), 11u);
  for (const Scan& s : used) EXPECT_TRUE(coverage.reference().at(s.stamp).has_value());

  const TrialSpan clipped = coverage.clip({'a', scans.front().stamp, scans.back().stamp});
  EXPECT_EQ(clipped.first, toStampNs(kT0 + 1.0));
  EXPECT_EQ(clipped.last, toStampNs(kT0 + 3.4));
  EXPECT_LE(clipped.first, used.front().stamp);
  EXPECT_GE(clipped.last, used.back().stamp);
}

TEST(ReferenceSpan, ReadToEndReadsTheScansAfterTheReferenceWithoutUsingThem) {
  // a source that keeps what it reads (the scan cache) must see the whole trial, also after the reference ends
  struct Counting : ScanSource {
    explicit Counting(std::vector<Scan> s) : scans(std::move(s)) {}
    bool next(Scan& scan) override {
      if (read >= scans.size()) return false;
      scan = scans[read++];
      return true;
    }
    std::vector<Scan> scans;
    std::size_t read = 0;
  };
  const auto scans = endStamped(40);
  for (const bool to_end : {false, true}) {
    auto counting = std::make_unique<Counting>(scans);
    const Counting* seen = counting.get();
    CoveredScanSource source(std::move(counting), TrialCoverage("ntu_day_01", reference(1.0, 3.4)), to_end);
    const auto used = drain(source);
    EXPECT_EQ(used.size(), 24u);
    EXPECT_EQ(used.back().stamp, scans[34].stamp);
    EXPECT_EQ(seen->read, to_end ? 40u : 36u);  // without: it stops at the first scan after the reference
  }
}

TEST(ReferenceSpan, WithoutReferenceEveryScanIsUsed) {
  const auto scans = endStamped(3);
  CoveredScanSource source(std::make_unique<VectorScanSource>(scans), TrialCoverage{});
  EXPECT_EQ(drain(source).size(), 3u);
}

TEST(ReferenceSpan, NoOverlapFailsNamingTrialStampAndSpan) {
  TrialCoverage coverage("kth_day_06", reference(10.0, 12.0));
  try {
    coverage.clip({'a', toStampNs(kT0), toStampNs(kT0 + 5.0)});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("kth_day_06"), std::string::npos) << msg;
    EXPECT_NE(msg.find(formatStamp(toStampNs(kT0))), std::string::npos) << msg;
    EXPECT_NE(msg.find(formatStamp(toStampNs(kT0 + 10.0))), std::string::npos) << msg;
    EXPECT_NE(msg.find(formatStamp(toStampNs(kT0 + 12.0))), std::string::npos) << msg;
  }
}

TEST(ReferenceSpan, GapInsideTheReferenceFailsTheRun) {
  const auto scans = endStamped(40);
  std::vector<StampedPose> poses;
  for (const auto& p : reference(0.0, 3.9).poses())
    if (toSeconds(p.stamp) - kT0 < 1.45 || toSeconds(p.stamp) - kT0 > 2.95) poses.push_back(p);  // 1.5 s gap
  CoveredScanSource source(std::make_unique<VectorScanSource>(scans),
                           TrialCoverage("tuhh_day_02", Trajectory(std::move(poses))));
  try {
    drain(source);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("tuhh_day_02"), std::string::npos) << msg;
    EXPECT_NE(msg.find(formatStamp(scans[15].stamp)), std::string::npos) << msg;  // the first scan in the gap
  }
}

TEST(ReferenceSpan, TenAndTwentyHertzReferencesInterpolateToKeyframeAndPointTimes) {
  for (const double rate : {10.0, 20.0}) {
    const Trajectory ref = reference(0.0, 4.0, rate);
    double worst_m = 0.0, worst_deg = 0.0;
    for (double t = 0.0; t <= 4.0; t += 0.0137) {  // keyframe and point times between the poses
      const auto p = ref.at(toStampNs(kT0 + t));
      ASSERT_TRUE(p.has_value());
      worst_m = std::max(worst_m, (p->translation() - truePose(t).translation()).norm());
      worst_deg = std::max(worst_deg, angleDeg(*p, truePose(t)));
    }
    // 1.2 m/s^2 lateral: the chord of 0.1 s deviates from the path by a h^2 / 8 = 1.5 mm
    EXPECT_LT(worst_m, 2e-3) << rate << " Hz";
    EXPECT_LT(worst_deg, 0.01) << rate << " Hz";
  }
}
