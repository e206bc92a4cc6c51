// The md5sum rule is checked against ROS's own generated md5sums (std_msgs/Header, geometry_msgs/Pose, and
// visualization_msgs/Marker, which has constants and nested and array fields); the PoseGraph md5sum is pinned
// to what genmsg 0.6.0 (Debian's python3-genmsg, gentools.compute_md5) computes from LAMP's original
// pose_graph_msgs/msg/*.msg files, comments included.
#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Vector3.h>
#include <ros/message_traits.h>
#include <std_msgs/ColorRGBA.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>

#include <gtest/gtest.h>

#include "cosmo/nebula/message_definition.hpp"

using namespace cosmo::nebula;
namespace mt = ros::message_traits;

namespace {

/// A generated definition without the appended dependency sections.
std::string ownText(const std::string& definition) {
  const std::size_t sep = definition.find("\n" + std::string(80, '='));
  return sep == std::string::npos ? definition : definition.substr(0, sep + 1);
}

template <typename M>
std::string md5() {
  return mt::MD5Sum<M>::value();
}

}  // namespace

TEST(MessageDefinition, NestedStandardMd5sumsAreROSs) {
  EXPECT_EQ(kHeaderMd5, md5<std_msgs::Header>());
  EXPECT_EQ(kPoseMd5, md5<geometry_msgs::Pose>());
}

TEST(MessageDefinition, RuleReproducesROSMd5sums) {
  EXPECT_EQ(md5Hex(md5Text(mt::Definition<std_msgs::Header>::value(), {})), md5<std_msgs::Header>());
  EXPECT_EQ(md5Hex(md5Text(ownText(mt::Definition<geometry_msgs::Pose>::value()),
                           {{"Point", md5<geometry_msgs::Point>()}, {"Quaternion", md5<geometry_msgs::Quaternion>()}})),
            md5<geometry_msgs::Pose>());
  const std::map<std::string, std::string> marker_nested{{"Header", md5<std_msgs::Header>()},
                                                         {"geometry_msgs/Pose", md5<geometry_msgs::Pose>()},
                                                         {"geometry_msgs/Vector3", md5<geometry_msgs::Vector3>()},
                                                         {"std_msgs/ColorRGBA", md5<std_msgs::ColorRGBA>()},
                                                         {"geometry_msgs/Point", md5<geometry_msgs::Point>()}};
  EXPECT_EQ(md5Hex(md5Text(ownText(mt::Definition<visualization_msgs::Marker>::value()), marker_nested)),
            md5<visualization_msgs::Marker>());
}

TEST(MessageDefinition, PoseGraphMd5sumMatchesGenmsg) {
  EXPECT_EQ(poseGraphNodeMd5(), "d08a6b4b5d6e4c60e98685622f399a1e");
  EXPECT_EQ(poseGraphEdgeMd5(), "cfc2854799a8a1ab8ac1f62511bb6216");
  EXPECT_EQ(poseGraphMd5(), "7bcbcc6a764387d0d037d9ff4f38d1b9");
}

TEST(MessageDefinition, CommentsAndSpacingDoNotChangeTheMd5sum) {
  EXPECT_EQ(md5Text("int32 A   = 3 # three\n\n# a comment\nfloat64[36] c  # cov\n", {}), "int32 A=3\nfloat64[36] c");
  EXPECT_EQ(md5Text("string S = a # not a comment\n", {}), "string S=a # not a comment");
  EXPECT_THROW(md5Text("Unknown x\n", {}), std::invalid_argument);
}

TEST(MessageDefinition, FullDefinitionListsEachDependencyOnce) {
  const std::string full = poseGraphFullDefinition(
      mt::Definition<std_msgs::Header>::value(), ownText(mt::Definition<geometry_msgs::Pose>::value()),
      mt::Definition<geometry_msgs::Point>::value(), mt::Definition<geometry_msgs::Quaternion>::value());
  for (const char* type : {"std_msgs/Header", "pose_graph_msgs/PoseGraphNode", "geometry_msgs/Pose",
                           "geometry_msgs/Point", "geometry_msgs/Quaternion", "pose_graph_msgs/PoseGraphEdge"}) {
    const std::string marker = "\nMSG: " + std::string(type) + "\n";
    EXPECT_NE(full.find(marker), std::string::npos) << type;
    EXPECT_EQ(full.find(marker), full.rfind(marker)) << type;
  }
  EXPECT_EQ(full.rfind("Header header\n", 0), 0u);
}
