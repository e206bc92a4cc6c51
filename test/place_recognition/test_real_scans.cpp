// ScanContext on real scans (../shared/data/scan_snippets): MulRan KAIST03 keyframes near pairs score lower
// than far pairs, and a rotated real scan gives its yaw. Skipped when ../shared is not there.
#include <gtest/gtest.h>

#include <cmath>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/place_recognition/scan_context.hpp"
#include "cosmo/test_support/sim_scenes.hpp"

namespace cosmo::place_recognition {
namespace {

using test_support::turnSensor;

TEST(RealScans, MulranNearPairsScoreLowerThanFarPairs) {
  const auto dir = sharedPath("data/scan_snippets/mulran_kaist03_keyframes");
  if (!dir) GTEST_SKIP() << "../shared/data/scan_snippets/mulran_kaist03_keyframes not found";
  const auto poses = readKittiPoses(*dir + "/optimized_poses.txt");
  const auto files = listScanFiles(*dir + "/Scans");
  ASSERT_EQ(files.size(), 21u);
  const ScanContextParams p;
  std::vector<ScanContext> sc;
  for (const auto& f : files) sc.push_back(makeScanContext(readScanFile(f), p));
  double near_max = 0.0, far_min = 1.0;
  int near_n = 0, far_n = 0;
  for (std::size_t i = 0; i < sc.size(); ++i)
    for (std::size_t j = i + 1; j < sc.size(); ++j) {
      const double sep = (poses[i].translation() - poses[j].translation()).norm();
      const double d = scanContextDistance(sc[j], sc[i]).distance;
      if (sep <= 3.0) {
        near_max = std::max(near_max, d);
        ++near_n;
      } else if (sep >= 15.0) {
        far_min = std::min(far_min, d);
        ++far_n;
      }
    }
  ASSERT_GT(near_n, 10);
  ASSERT_GT(far_n, 10);
  // Measured: near <= 0.18, far >= 0.36 (bench_scancontext); require a clear gap.
  EXPECT_LT(near_max + 0.1, far_min) << "near max " << near_max << " far min " << far_min;
}

TEST(RealScans, RotatedRealScanGivesItsYaw) {
  const auto dir = sharedPath("data/scan_snippets/kitti00/velodyne");
  if (!dir) GTEST_SKIP() << "../shared/data/scan_snippets/kitti00 not found";
  const ScanContextParams p;
  const Scan scan = readScanFile(*dir + "/000094.bin");
  const ScanContext c = makeScanContext(scan, p);
  for (const double yaw : {0.3, 1.7, -2.6}) {
    const DescriptorMatch m = scanContextDistance(makeScanContext(turnSensor(scan, yaw), p), c);
    EXPECT_LE(std::abs(std::remainder(m.yaw - yaw, 2.0 * M_PI)), 2.0 * M_PI / p.sectors) << "yaw " << yaw;
    EXPECT_LT(m.distance, 0.2);
  }
}

}  // namespace
}  // namespace cosmo::place_recognition
