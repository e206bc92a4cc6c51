// KeyframeTaker: the keyframer's decisions on the poses it is fed, and the keyframe scan it makes: points only,
// without NaN or too-close points, dewarped with the reference when there is one, else with the odometry of the
// sweep (the previous scan's pose and this one).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cosmo/frontend/keyframe_taker.hpp"

using namespace cosmo;
using namespace cosmo::frontend;

namespace {
constexpr StampNs kSecond = 1000000000ULL;

/// Two points seen at the start and at the end of a 0.1 s sweep, one NaN and one at 0.5 m.
Scan sweep(StampNs stamp) {
  Scan s;
  s.stamp = stamp;
  s.points = {{10.0f, 0.0f, 0.0f},
              {10.0f, 0.0f, 0.0f},
              {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f},
              {0.5f, 0.0f, 0.0f}};
  s.time = {-0.1f, 0.0f, -0.05f, 0.0f};
  return s;
}
}  // namespace

TEST(KeyframeTaker, KeyframesEveryTwoMetresOfPath) {
  FrontendParams params;  // d_kf = 2 m
  KeyframeTaker taker(params);
  std::vector<std::size_t> keyframes;
  for (int i = 0; i < 12; ++i) {  // 0.5 m per scan
    const odometry::KeyframeDecision d =
        taker.update(10 * kSecond + i * kSecond / 10, makePose(0.5 * i, 0, 0, 0, 0, 0));
    if (d.is_keyframe) keyframes.push_back(static_cast<std::size_t>(i));
  }
  EXPECT_EQ(keyframes, (std::vector<std::size_t>{0, 5, 10}));  // more than 2 m: after 2.5 m
}

TEST(KeyframeTaker, KeyframeScanIsDewarpedWithTheReferenceElseTheOdometry) {
  FrontendParams params;
  params.keyframe_min_range = 1.0;
  const StampNs t0 = 10 * kSecond, t1 = t0 + kSecond / 10;
  // The sensor moves +1 m in x over the sweep: a point seen 10 m ahead at the sweep's start is 9 m ahead at its end.
  KeyframeTaker taker(params);
  taker.update(t0, makePose(0, 0, 0, 0, 0, 0));
  taker.update(t1, makePose(1, 0, 0, 0, 0, 0));
  const Scan by_odometry = taker.keyframeScan(sweep(t1), Trajectory{});
  ASSERT_EQ(by_odometry.size(), 2u);  // NaN and the 0.5 m point dropped
  EXPECT_EQ(by_odometry.stamp, t1);
  EXPECT_TRUE(by_odometry.time.empty());
  EXPECT_NEAR(by_odometry.points[0].x(), 9.0f, 1e-4);
  EXPECT_NEAR(by_odometry.points[1].x(), 10.0f, 1e-4);

  // A reference that did not move over the sweep: nothing to correct, whatever the odometry says.
  const Trajectory still({{t0 - kSecond, makePose(5, 5, 0, 0, 0, 0)}, {t1 + kSecond, makePose(5, 5, 0, 0, 0, 0)}});
  const Scan by_reference = taker.keyframeScan(sweep(t1), still);
  ASSERT_EQ(by_reference.size(), 2u);
  EXPECT_NEAR(by_reference.points[0].x(), 10.0f, 1e-4);

  params.dewarp_with_reference = false;  // the odometry even with a reference
  KeyframeTaker odometry_only(params);
  odometry_only.update(t0, makePose(0, 0, 0, 0, 0, 0));
  odometry_only.update(t1, makePose(1, 0, 0, 0, 0, 0));
  EXPECT_NEAR(odometry_only.keyframeScan(sweep(t1), still).points[0].x(), 9.0f, 1e-4);
}
