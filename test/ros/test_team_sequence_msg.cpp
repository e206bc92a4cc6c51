// The resolved sequence as the player hands it over ROS (ros/team_sequence_msg.hpp): a reference trajectory
// comes back bit-exact (the lockstep JRL is byte-identical to the offline driver's), a malformed one is refused
// naming the topic and field, and the sequence message carries robots, trials, spans and seed.
#include <gtest/gtest.h>

#include <cmath>

#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {
Trajectory awkwardTrajectory() {
  Trajectory t;
  for (int i = 0; i < 50; ++i) {
    const double a = 0.1 * i + 1.0 / 3.0;
    Pose3 p = makePose(Eigen::Vector3d(std::sqrt(2.0) * i, -1.0 / 7.0 * i, 1e-9 * i),
                       Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d(1, 2, 3).normalized())));
    t.append(1700000000000000000ULL + 100000007ULL * static_cast<StampNs>(i), p);
  }
  return t;
}
}  // namespace

TEST(TeamSequenceMsg, AReferenceTrajectoryComesBackBitExact) {
  const Trajectory t = awkwardTrajectory();
  const cosmo::ReferenceTrajectory m = ros_glue::trajectoryToMsg('c', t, "world");
  EXPECT_EQ(m.robot, "c");
  EXPECT_EQ(m.header.frame_id, "world");
  const Trajectory back = ros_glue::trajectoryFromMsg(m, "/c/reference_trajectory");
  ASSERT_EQ(back.size(), t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(back.poses()[i].stamp, t.poses()[i].stamp);
    EXPECT_TRUE(back.poses()[i].pose.matrix() == t.poses()[i].pose.matrix()) << "pose " << i;
  }
  const StampNs mid = t.poses()[10].stamp + 12345;
  EXPECT_TRUE(back.atClamped(mid).matrix() == t.atClamped(mid).matrix());
}

TEST(TeamSequenceMsg, NoPosesIsNoReference) {
  const Trajectory back = ros_glue::trajectoryFromMsg(ros_glue::trajectoryToMsg('a', Trajectory{}, "world"), "t");
  EXPECT_TRUE(back.empty());
}

TEST(TeamSequenceMsg, AMalformedTrajectoryIsRefusedNamingTopicAndField) {
  cosmo::ReferenceTrajectory m = ros_glue::trajectoryToMsg('a', awkwardTrajectory(), "world");
  m.poses.pop_back();
  try {
    ros_glue::trajectoryFromMsg(m, "/a/reference_trajectory");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/a/reference_trajectory: poses"), std::string::npos) << e.what();
  }
  m = ros_glue::trajectoryToMsg('a', awkwardTrajectory(), "world");
  std::swap(m.stamps[3], m.stamps[4]);
  EXPECT_THROW(ros_glue::trajectoryFromMsg(m, "/a/reference_trajectory"), std::runtime_error);
}

TEST(TeamSequenceMsg, TheSequenceCarriesRobotsTrialsSpansAndSeed) {
  sequence::SequenceConfig config;
  config.name = "team";
  config.seed = 18446744073709551557ULL;  // 64 bits survive
  for (char r : {'a', 'b'}) {
    sequence::TrialConfig t;
    t.robot = r;
    t.name = std::string("trial_") + r;
    config.trials.push_back(t);
  }
  config.anchor = 'a';
  const sequence::SequenceTiming timing = sequence::SequenceTiming::synchronize(
      {{'a', 1000000000ULL, 5000000000ULL}, {'b', 2000000000ULL, 9000000000ULL}}, 'a', 0.0, 1);
  const cosmo::TeamSequence m = ros_glue::teamSequenceToMsg(config, timing);
  EXPECT_EQ(m.name, "team");
  EXPECT_EQ(m.seed, config.seed);
  EXPECT_EQ(m.robots, "ab");
  EXPECT_EQ(m.trials, (std::vector<std::string>{"trial_a", "trial_b"}));
  EXPECT_EQ(m.start.toNSec(), timing.start());
  EXPECT_EQ(m.end.toNSec(), timing.end());
  ASSERT_EQ(m.first.size(), 2u);
  EXPECT_EQ(m.first[1].toNSec(), timing.of('b').start());
  EXPECT_EQ(m.last[1].toNSec(), timing.of('b').end());
}
