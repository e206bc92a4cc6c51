// rostest gtest node for team6.test: six robots from the sequence alone. Counts the keyframes every robot's
// front-end publishes (/<r>/keyframes_meas), waits for the player to finish, makes the recorder write, and checks
// that the JRL holds the six robots, each with its prior and an odometry chain, and passes validation.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <vector>

#include "cosmo/RecorderKeyframe.h"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"

namespace {
const std::vector<char> kRobots = {'a', 'b', 'c', 'd', 'e', 'f'};
}

TEST(TeamOfSix, EveryFrontendRunsAndTheJrlHasSixRobots) {
  ros::NodeHandle nh;
  std::string jrl_path;
  ASSERT_TRUE(nh.getParam("/jrl_path", jrl_path));
  std::atomic<bool> done{false};
  std::map<char, std::atomic<int>> keyframes;
  std::vector<ros::Subscriber> subs;
  for (char r : kRobots) {
    keyframes[r] = 0;
    subs.push_back(nh.subscribe<cosmo::RecorderKeyframe>(
        std::string("/") + r + "/keyframes_meas", 1000,
        [&keyframes, r](const cosmo::RecorderKeyframe::ConstPtr&) { ++keyframes[r]; }));
  }
  subs.push_back(
      nh.subscribe<std_msgs::Empty>("/player/done", 1, [&](const std_msgs::Empty::ConstPtr&) { done = true; }));
  const ros::WallTime start = ros::WallTime::now();
  while (ros::ok() && !done && (ros::WallTime::now() - start).toSec() < 360.0) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(done) << "the player did not finish";
  for (int i = 0; i < 20; ++i) {  // what is still in flight
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  std::vector<std::string> robots;
  ASSERT_TRUE(nh.getParam("/player/robots", robots));
  EXPECT_EQ(robots.size(), kRobots.size());
  for (char r : kRobots) EXPECT_GE(keyframes[r].load(), 2) << "front-end " << r << " published too few keyframes";

  ASSERT_TRUE(ros::service::waitForService("/recorder/write", ros::Duration(30.0)));
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("/recorder/write", trigger));
  EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  ASSERT_TRUE(std::filesystem::exists(jrl_path)) << jrl_path;
  const cosmo::jrl::Dataset ds = cosmo::jrl::readJrl(jrl_path);
  for (const auto& v : cosmo::jrl::validate(ds)) ADD_FAILURE() << v.str();
  const auto stats = cosmo::jrl::computeStats(ds);
  std::cout << cosmo::jrl::formatStats(stats) << std::endl;
  EXPECT_EQ(ds.robots, kRobots);
  EXPECT_EQ(stats.priors, kRobots.size());
  for (char r : kRobots) EXPECT_GE(ds.measurements.at(r).size(), 2u) << "robot " << r << " has no odometry in the JRL";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "team6_test");
  ros::NodeHandle nh;  // keeps the node up across the tests
  return RUN_ALL_TESTS();
}
