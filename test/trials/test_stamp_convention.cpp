// The stamp convention of a trial (`stamp: start | end`) honoured where scans are decoded: a start-stamped and an
// end-stamped copy of the same organised Ouster sweeps decode to the same scans, bit for bit (stamped at the sweep
// end), so the pipeline's odometry over them (through the trial's CoveredScanSource) is the same too.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/test_support/sim_scenes.hpp"
#include "cosmo/sequence/trial_coverage.hpp"
#include "cosmo/trials/ouster_cloud.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"

using namespace cosmo;

namespace {

constexpr double kT0 = 1.7e9;

Pose3 truePose(double t) {
  Pose3 p = Pose3::Identity();
  p.linear() = (Eigen::AngleAxisd(0.15 * t, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.01 * std::sin(3.0 * t), Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  p.translation() = Eigen::Vector3d(8.0 * t, 0.6 * t * t, 0.0);
  return p;
}

trials::OusterSweep sweepOf(bool stamp_at_end) {
  trials::OusterSweep s;
  s.beams = 16;
  s.columns = 500;  // a column of 200 us: header stamps in whole ns for either convention
  s.rate_hz = 10.0;
  s.stamp_at_end = stamp_at_end;
  return s;
}

/// n simulated sweeps written as organised Ouster clouds with the given convention and decoded with it.
std::vector<Scan> decodedSweeps(int n, bool stamp_at_end) {
  static const sim::World scene = test_support::streetWorld(300.0);
  sim::LidarModel lidar = test_support::idealLidar();
  lidar.beams = 16;
  lidar.columns = 500;
  std::vector<Scan> out;
  for (int k = 0; k < n; ++k) {
    const double t_end = 0.1 * k;
    const Scan sim = test_support::simulateSweep(scene, lidar, toStampNs(kT0 + t_end),
                                                 [&](double dt) { return truePose(t_end + dt); });
    const trials::RawCloud cloud = trials::organisedOusterCloud(sim, sweepOf(stamp_at_end));
    Scan s;
    trials::decodeCloud(cloud.layout, cloud.data.data(), cloud.data.size(), stamp_at_end, "test", s);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

TEST(StampConvention, StartAndEndStampedCopiesDecodeToTheSameScans) {
  const auto end = decodedSweeps(3, true), start = decodedSweeps(3, false);
  for (std::size_t k = 0; k < end.size(); ++k) {
    EXPECT_EQ(start[k].stamp, end[k].stamp) << "scan " << k;
    EXPECT_EQ(start[k].points, end[k].points);
    EXPECT_EQ(start[k].time, end[k].time);
    EXPECT_EQ(start[k].ring, end[k].ring);
    for (float t : end[k].time) ASSERT_LE(t, 0.0f);  // stamped at the sweep end
  }
}

TEST(StampConvention, SameOdometryFromBothCopies) {
  auto run = [](std::vector<Scan> scans) {
    sequence::CoveredScanSource source(std::make_unique<sequence::VectorScanSource>(std::move(scans)),
                                       sequence::TrialCoverage{});
    odometry::LoamOdometry odom;
    std::vector<std::pair<StampNs, Pose3>> poses;
    Scan s;
    while (source.next(s)) {
      const odometry::OdometryResult r = odom.update(s);
      EXPECT_TRUE(r.ok) << r.warning;
      poses.push_back({s.stamp, r.pose});
    }
    return poses;
  };
  const auto from_end = run(decodedSweeps(20, true));
  const auto from_start = run(decodedSweeps(20, false));
  ASSERT_EQ(from_end.size(), from_start.size());
  for (std::size_t k = 0; k < from_end.size(); ++k) {
    EXPECT_EQ(from_end[k].first, from_start[k].first);
    EXPECT_TRUE(from_end[k].second.isApprox(from_start[k].second, 0.0)) << "scan " << k;
  }
  const Pose3 truth = truePose(0.0).inverse() * truePose(1.9);
  EXPECT_LT((from_end.back().second.translation() - truth.translation()).norm(), 0.5);
}
