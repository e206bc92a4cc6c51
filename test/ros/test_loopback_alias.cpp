// Which ROS_IP / ROS_HOSTNAME make roscpp 1.15 serve a node's topics where no peer can reach them (127.0.0.1 only,
// while it registers another address), and that the node then runs as ROS_HOSTNAME=<that address>.
#include <gtest/gtest.h>

#include <cstdlib>

#include "cosmo/ros/loopback_alias.hpp"

using cosmo::ros_glue::RosAddressEnv;
using cosmo::ros_glue::unreachableTopicAddress;

TEST(LoopbackAlias, OnlyALoopbackAliasOtherThan127001IsUnreachable) {
  EXPECT_EQ(unreachableTopicAddress({"127.0.0.2", std::nullopt}), std::optional<std::string>("127.0.0.2"));
  EXPECT_EQ(unreachableTopicAddress({"127.1.2.3", std::nullopt}), std::optional<std::string>("127.1.2.3"));
  EXPECT_FALSE(unreachableTopicAddress({"127.0.0.1", std::nullopt}));    // bound where it registers
  EXPECT_FALSE(unreachableTopicAddress({"10.0.0.2", std::nullopt}));     // bound to every address
  EXPECT_FALSE(unreachableTopicAddress({std::nullopt, "127.0.0.2"}));    // ROS_HOSTNAME: every address
  EXPECT_FALSE(unreachableTopicAddress({std::nullopt, "localhost"}));    // 127.0.0.1, registered as localhost
  EXPECT_FALSE(unreachableTopicAddress({std::nullopt, std::nullopt}));  // the host name, every address
  // ROS_HOSTNAME names the registered address, and ROS_IP=127.x still binds to 127.0.0.1
  EXPECT_EQ(unreachableTopicAddress({"127.0.0.1", "10.0.0.2"}), std::optional<std::string>("10.0.0.2"));
  EXPECT_FALSE(unreachableTopicAddress({"10.0.0.3", "10.0.0.2"}));
}

TEST(LoopbackAlias, TheNodeRunsAsRosHostnameOfItsAddress) {
  setenv("ROS_IP", "127.0.0.3", 1);
  unsetenv("ROS_HOSTNAME");
  const std::string note = cosmo::ros_glue::serveTopicsWhereRegistered();
  EXPECT_NE(note.find("ROS_IP=127.0.0.3"), std::string::npos) << note;
  EXPECT_EQ(std::getenv("ROS_IP"), nullptr);
  ASSERT_NE(std::getenv("ROS_HOSTNAME"), nullptr);
  EXPECT_STREQ(std::getenv("ROS_HOSTNAME"), "127.0.0.3");
  EXPECT_EQ(cosmo::ros_glue::serveTopicsWhereRegistered(), "");  // nothing left to do
  unsetenv("ROS_HOSTNAME");
}
