#include <gtest/gtest.h>

#include <random>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/trajectory.hpp"

using namespace cosmo;

TEST(Pose, ExpLogRoundTripIncludingNearPi) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    Vector6 xi;
    for (int k = 0; k < 6; ++k) xi[k] = 3.0 * u(rng);
    if (xi.head<3>().norm() >= M_PI) xi.head<3>() *= 0.99 * M_PI / xi.head<3>().norm();
    const Pose3 T = expSE3(xi);
    EXPECT_LT((logSE3(T) - xi).norm(), 1e-9) << "i=" << i;
  }
  Vector6 tiny = Vector6::Constant(1e-10);
  EXPECT_LT((logSE3(expSE3(tiny)) - tiny).norm(), 1e-15);
}

TEST(Pose, LogOfKnownRotationAndTranslation) {
  const Pose3 T = makePose(1.0, 2.0, 3.0, 0.0, 0.0, M_PI / 2);
  const Vector6 xi = logSE3(T);
  EXPECT_NEAR(xi[2], M_PI / 2, 1e-12);
  EXPECT_NEAR(xi.head<2>().norm(), 0.0, 1e-12);
  EXPECT_LT((expSE3(xi).matrix() - T.matrix()).norm(), 1e-12);
  EXPECT_NEAR(yawOf(T), M_PI / 2, 1e-12);
  EXPECT_NEAR(rotationAngle(T), M_PI / 2, 1e-12);
}

TEST(Trajectory, InterpolatesAndClamps) {
  Trajectory traj;
  traj.append(1000, makePose(0, 0, 0, 0, 0, 0));
  traj.append(3000, makePose(2, 0, 0, 0, 0, 1.0));
  const Pose3 mid = traj.atClamped(2000);
  EXPECT_NEAR(mid.translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(yawOf(mid), 0.5, 1e-12);
  EXPECT_FALSE(traj.at(999).has_value());
  EXPECT_NEAR(traj.atClamped(5000).translation().x(), 2.0, 1e-12);
  EXPECT_NEAR(traj.length(), 2.0, 1e-12);
  EXPECT_THROW(traj.append(2000, Pose3::Identity()), std::invalid_argument);
  EXPECT_EQ(traj.shifted(-500).startStamp(), 500u);
}
