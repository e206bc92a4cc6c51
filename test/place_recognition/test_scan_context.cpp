// ScanContext descriptor and distance: ring-key rotation invariance, yaw recovery, empty/degenerate input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cosmo/place_recognition/scan_context.hpp"
#include "cosmo/test_support/sim_scenes.hpp"

namespace cosmo::place_recognition {
namespace {

const sim::World& scene() {
  static const sim::World s = test_support::pillarWorld(7);
  return s;
}

double sectorWidth(const ScanContextParams& p) { return 2.0 * M_PI / p.sectors; }

double angleDiff(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

TEST(ScanContext, ShapeAndBinValues) {
  ScanContextParams p;
  Scan scan;
  scan.points = {{10.0f, 0.1f, 1.0f}, {10.2f, 0.1f, 3.0f}, {0.1f, -10.0f, -1.0f}, {-100.0f, 0.0f, 0.0f}};
  const ScanContext sc = makeScanContext(scan, p);
  ASSERT_EQ(sc.descriptor.rows(), 20);
  ASSERT_EQ(sc.descriptor.cols(), 60);
  // ring 2 (8..12 m), sector 0: the maximum of 1 + 2 and 3 + 2.
  EXPECT_FLOAT_EQ(sc.descriptor(2, 0), 5.0f);
  // azimuth -90 deg = 270 deg -> sector 45, height -1 + 2 = 1.
  EXPECT_FLOAT_EQ(sc.descriptor(2, 45), 1.0f);
  EXPECT_EQ((sc.descriptor.array() > 0.0f).count(), 2);  // the 100 m point is out of range
  EXPECT_FLOAT_EQ(sc.ring_key(2), 2.0f / 60.0f);
  EXPECT_FLOAT_EQ(sc.sector_key(0), 5.0f / 20.0f);
}

TEST(ScanContext, RingKeyIsRotationInvariant) {
  const ScanContextParams p;
  const Scan scan = test_support::scanAt(scene(), 12.0, -30.0, 0.3);
  const ScanContext sc = makeScanContext(scan, p);
  ASSERT_GT(sc.ring_key.sum(), 1.0f);
  // Whole-sector turns move whole columns: the ring key is the same up to points on sector borders.
  for (int k : {1, 7, 30, 59}) {
    const ScanContext turned = makeScanContext(test_support::turnSensor(scan, k * sectorWidth(p)), p);
    EXPECT_LE((turned.ring_key - sc.ring_key).cwiseAbs().maxCoeff(), 2.0f / 60.0f + 1e-6f) << "k=" << k;
  }
  // Arbitrary turns re-bin the points, which moves the ring key a little, but much less than moving to another
  // place: among 20 places, the turned scan's nearest ring key is still its own.
  std::vector<Eigen::VectorXf> others;
  for (int i = 0; i < 20; ++i)
    others.push_back(
        makeScanContext(test_support::scanAt(scene(), -120.0 + 13.0 * i, 40.0 - 7.0 * i, 0.0), p).ring_key);
  for (double yaw : {0.05, 1.0, -2.2, 3.1}) {
    const ScanContext turned = makeScanContext(test_support::turnSensor(scan, yaw), p);
    const float own = (turned.ring_key - sc.ring_key).norm();
    for (const auto& o : others) EXPECT_LT(own, (turned.ring_key - o).norm()) << "yaw=" << yaw;
  }
}

TEST(ScanContext, RotatedScanGivesItsYaw) {
  const ScanContextParams p;
  const Scan scan = test_support::scanAt(scene(), -40.0, 25.0, 1.0);
  const ScanContext candidate = makeScanContext(scan, p);
  for (int k : {1, 5, 15, 29, 30, 31, 45, 59}) {  // exact sector multiples: exact shift
    const ScanContext query = makeScanContext(test_support::turnSensor(scan, k * sectorWidth(p)), p);
    const DescriptorMatch m = scanContextDistance(query, candidate);
    EXPECT_EQ(m.shift, k);
    EXPECT_LT(m.distance, 0.05);
    EXPECT_NEAR(angleDiff(m.yaw, k * sectorWidth(p)), 0.0, 1e-9);
  }
  for (double yaw : {0.2, -0.7, 1.9, -2.9, 3.0}) {  // any yaw: within one sector
    const ScanContext query = makeScanContext(test_support::turnSensor(scan, yaw), p);
    const DescriptorMatch m = scanContextDistance(query, candidate);
    EXPECT_LE(angleDiff(m.yaw, yaw), sectorWidth(p)) << "yaw=" << yaw << " estimate=" << m.yaw;
    EXPECT_LT(m.distance, 0.25);
    EXPECT_GT(m.yaw, -M_PI);
    EXPECT_LE(m.yaw, M_PI);
  }
  // Self-distance is zero at shift 0, and another place is far.
  EXPECT_NEAR(scanContextDistance(candidate, candidate).distance, 0.0, 1e-6);
  EXPECT_EQ(scanContextDistance(candidate, candidate).shift, 0);
  const ScanContext elsewhere = makeScanContext(test_support::scanAt(scene(), 90.0, -100.0, 1.0), p);
  EXPECT_GT(scanContextDistance(elsewhere, candidate).distance, 0.4);
}

TEST(ScanContext, CoarseSearchFindsTheSameShiftOnAClearRotation) {
  const ScanContextParams p;
  const Scan scan = test_support::scanAt(scene(), 5.0, 5.0, 0.0);
  const ScanContext candidate = makeScanContext(scan, p);
  const ScanContext query = makeScanContext(test_support::turnSensor(scan, 20 * sectorWidth(p)), p);
  EXPECT_EQ(sectorKeyShift(query, candidate), 20);
  const DescriptorMatch coarse =
      scanContextDistance(query, candidate, EmptyColumnPolicy::kPenalizeOneSided, /*coarse_search_radius=*/3);
  EXPECT_EQ(coarse.shift, 20);
}

TEST(ScanContext, EmptyColumnPolicies) {
  ScanContextParams p;
  p.rings = 2;
  p.sectors = 4;
  p.max_range = 20.0;
  p.sensor_height = 0.0;
  ScanContext q, c;
  q.descriptor = Eigen::MatrixXf::Zero(2, 4);
  c.descriptor = Eigen::MatrixXf::Zero(2, 4);
  q.descriptor.col(0) << 1.0f, 2.0f;  // occupied columns: q {0, 1}, c {0}
  q.descriptor.col(1) << 3.0f, 1.0f;
  c.descriptor.col(0) << 1.0f, 2.0f;
  // Shift 0: column 0 identical (distance 0), column 1 one-sided.
  EXPECT_NEAR(scanContextDistance(q, c, EmptyColumnPolicy::kSkipIfEitherEmpty).distance, 0.0, 1e-6);
  EXPECT_NEAR(scanContextDistance(q, c, EmptyColumnPolicy::kPenalizeOneSided).distance, 0.5, 1e-6);
  // All-empty descriptors share nothing: distance 1, no NaN.
  ScanContext e;
  e.descriptor = Eigen::MatrixXf::Zero(2, 4);
  EXPECT_EQ(scanContextDistance(e, e).distance, 1.0);
  EXPECT_EQ(scanContextDistance(q, e, EmptyColumnPolicy::kSkipIfEitherEmpty).distance, 1.0);
  // Sizes must agree.
  ScanContext big;
  big.descriptor = Eigen::MatrixXf::Zero(3, 4);
  EXPECT_THROW(scanContextDistance(q, big), std::invalid_argument);
}

TEST(ScanContext, DegenerateScans) {
  const ScanContextParams p;
  const ScanContext empty = makeScanContext(Scan{}, p);
  EXPECT_EQ(empty.descriptor.rows(), 20);
  EXPECT_EQ(empty.descriptor.count(), 0);
  EXPECT_EQ(empty.ring_key.sum(), 0.0f);
  Scan bad;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  bad.points = {{nan, 1.0f, 0.0f}, {1.0f, nan, 0.0f}, {1.0f, 1.0f, nan}, {inf, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
  const ScanContext sc = makeScanContext(bad, p);
  EXPECT_TRUE(sc.descriptor.allFinite());
  EXPECT_EQ((sc.descriptor.array() > 0.0f).count(), 1);  // only the origin point (height 2) counts
  EXPECT_EQ(scanContextDistance(empty, sc).distance, 1.0);
}

TEST(ScanContext, PointStrideKeepsTheDescriptorClose) {
  ScanContextParams p;
  const Scan scan = test_support::scanAt(scene(), 0.0, 0.0, 0.0);
  const ScanContext full = makeScanContext(scan, p);
  p.point_stride = 2;
  const ScanContext thin = makeScanContext(scan, p);
  EXPECT_LT(scanContextDistance(thin, full).distance, 0.15);
}

// The shipped file against the defaults: test/pipeline/test_parameter_lists.cpp (every listed parameter).
TEST(ScanContext, ParamsFromConfigValidation) {
  ConfigNode bad;
  bad.node = YAML::Load("scan_context: {rings: 0}");
  bad.where = "test.yaml: ";
  EXPECT_THROW(ScanContextParams::fromConfig(bad), std::runtime_error);
  bad.node = YAML::Load("scan_context: {empty_columns: sometimes}");
  EXPECT_THROW(ScanContextParams::fromConfig(bad), std::runtime_error);
}

}  // namespace
}  // namespace cosmo::place_recognition
