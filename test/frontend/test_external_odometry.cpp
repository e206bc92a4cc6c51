// Odometry from another source (frontend/external_odometry.hpp): interpolated between the poses around a stamp,
// the newest held a short while, nothing before the first pose kept.
#include <gtest/gtest.h>

#include "cosmo/frontend/external_odometry.hpp"

using namespace cosmo;
using namespace cosmo::frontend;

namespace {
constexpr StampNs kMs = 1000000ULL;
Pose3 at(double x) { return makePose(Eigen::Vector3d(x, 0, 0), Eigen::Quaterniond::Identity()); }
}  // namespace

TEST(ExternalOdometry, InterpolatesBetweenThePosesAroundTheStamp) {
  ExternalOdometry odom;
  odom.add(1000 * kMs, at(0.0));
  odom.add(1100 * kMs, at(1.0));
  odom.add(1200 * kMs, at(3.0));
  EXPECT_NEAR(odom.at(1050 * kMs)->translation().x(), 0.5, 1e-12);
  EXPECT_NEAR(odom.at(1150 * kMs)->translation().x(), 2.0, 1e-12);
  EXPECT_NEAR(odom.at(1100 * kMs)->translation().x(), 1.0, 1e-12);
}

TEST(ExternalOdometry, HoldsTheNewestPoseBrieflyAndNothingBeforeTheFirst) {
  ExternalOdometry odom(2000, 200 * kMs);
  EXPECT_FALSE(odom.at(1000 * kMs));
  odom.add(1000 * kMs, at(2.0));
  EXPECT_FALSE(odom.at(999 * kMs));
  EXPECT_NEAR(odom.at(1199 * kMs)->translation().x(), 2.0, 1e-12);
  EXPECT_FALSE(odom.at(1200 * kMs));
}

TEST(ExternalOdometry, KeepsOnlyTheLatestPoses) {
  ExternalOdometry odom(2);
  odom.add(1000 * kMs, at(0.0));
  odom.add(1100 * kMs, at(1.0));
  odom.add(1200 * kMs, at(2.0));
  EXPECT_FALSE(odom.at(1050 * kMs));
  EXPECT_NEAR(odom.at(1150 * kMs)->translation().x(), 1.5, 1e-12);
}
