// The radio-stepping rule both drivers share (team_radio.hpp): grid origin, step stamps, which steps run, the
// robot states they ask for and the stamps deliveries are handed over with.
#include <gtest/gtest.h>

#include <vector>

#include "cosmo/pipeline/team_radio.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

TEST(TeamRadio, GridOriginIsTheStartRoundedDownToTheAbsoluteGrid) {
  EXPECT_EQ(radioGridOrigin(1700000000123456789ULL, 0.1), 1700000000100000000ULL);
  EXPECT_EQ(radioGridOrigin(1700000000200000000ULL, 0.1), 1700000000200000000ULL);
  EXPECT_EQ(radioStepStamp(1000000000ULL, 0.3), 1300000000ULL);
}

TEST(TeamRadio, PositionFromTheReferenceHeldAtItsEndsElseOdometry) {
  Trajectory ref;
  Pose3 a = Pose3::Identity(), b = Pose3::Identity();
  b.translation() = Eigen::Vector3d(10, 0, 0);
  ref.append(1000, a);
  ref.append(3000, b);
  const Eigen::Vector3d odom(1, 2, 3);
  EXPECT_NEAR(radioPosition(ref, 2000, odom).x(), 5.0, 1e-12);
  EXPECT_NEAR(radioPosition(ref, 9000, odom).x(), 10.0, 1e-12);
  EXPECT_NEAR(radioPosition(ref, 0, odom).x(), 0.0, 1e-12);
  EXPECT_EQ(radioPosition(Trajectory{}, 2000, odom), odom);
}

TEST(TeamRadio, RunsEveryStepUpToTAndDeliversAtTheStepStamp) {
  comm::RadioParams params = comm::RadioParams::wifi();
  comm::RadioSimulator radio(params, {'a', 'b'}, 7);
  const StampNs origin = 5000000000ULL;
  std::vector<StampNs> asked;
  const auto state = [&](char robot, StampNs stamp) {
    if (robot == 'a') asked.push_back(stamp);
    RadioRobotState s;
    s.on = true;
    s.position = Eigen::Vector3d(robot == 'a' ? 0.0 : 5.0, 0, 0);  // close: a link starts
    return s;
  };
  std::vector<std::pair<StampNs, comm::Transfer>> ended;
  const auto on_transfer = [&](StampNs stamp, const comm::Transfer& t) { ended.emplace_back(stamp, t); };

  EXPECT_EQ(advanceRadio(radio, origin, origin - 1, state, on_transfer), 0u);             // before the origin: nothing
  EXPECT_EQ(advanceRadio(radio, origin, origin + 250000000ULL, state, on_transfer), 3u);  // 0, 0.1, 0.2 s
  ASSERT_EQ(asked.size(), 3u);
  EXPECT_EQ(asked[0], origin);
  EXPECT_EQ(asked[2], origin + 200000000ULL);
  EXPECT_EQ(advanceRadio(radio, origin, origin + 250000000ULL, state, on_transfer), 0u);  // already there

  radio.offerKeyframe('a', 0, 1000, 1000);  // 1 kB: through within a few steps at 2 MB/s
  advanceRadio(radio, origin, origin + 2000000000ULL, state, on_transfer);
  ASSERT_FALSE(ended.empty());
  const auto& [stamp, transfer] = ended.front();
  EXPECT_EQ(transfer.sender, 'a');
  EXPECT_EQ(transfer.receiver, 'b');
  EXPECT_EQ(stamp, radioStepStamp(origin, transfer.end));  // handed over at the step it ended in
  EXPECT_EQ((stamp - origin) % 100000000ULL, 0u);
}
