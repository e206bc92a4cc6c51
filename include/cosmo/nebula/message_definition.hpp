#pragma once
// The pose_graph_msgs/PoseGraph definition and its ROS 1 md5sum, computed by ROS's rule rather than copied:
// the md5 text of a message is its constants ("type NAME=value", in order), then its fields, one per line:
// "type name" for built-in types (array suffix kept, e.g. "float64[36] covariance"), "<md5 of the nested
// type> name" for message types (array suffix dropped); comments and blank lines removed, trailing newline
// stripped; the md5sum is the hex MD5 of that text. Nested types resolve depth first: PoseGraph needs the
// md5 of std_msgs/Header, PoseGraphNode and PoseGraphEdge, which need geometry_msgs/Pose.
#include <map>
#include <string>
#include <string_view>

namespace cosmo::nebula {

constexpr const char* kPoseGraphType = "pose_graph_msgs/PoseGraph";

/// md5sums of the standard nested types (std_msgs/Header, geometry_msgs/Pose as Debian's ROS generates
/// them; test_message_definition checks them against the installed ROS headers and against md5Text()).
constexpr const char* kHeaderMd5 = "2176decaecbce78abc3b96ef049fabed";
constexpr const char* kPoseMd5 = "e45d45a5a1ce597b249e23fb30fc871f";

/// The .msg texts of LAMP's pose_graph_msgs: their fields and constants, without comments.
std::string_view poseGraphMsgText();
std::string_view poseGraphNodeMsgText();
std::string_view poseGraphEdgeMsgText();

/// ROS 1 md5 text of a .msg text. `nested_md5` maps a field type as written ("Header",
/// "geometry_msgs/Pose", "PoseGraphNode") to that type's md5sum; throws std::invalid_argument naming the type
/// when a non-built-in type is missing from it, or a line that is not a field or a constant.
std::string md5Text(std::string_view msg_text, const std::map<std::string, std::string>& nested_md5);

/// Lower-case hex MD5 of `bytes`.
std::string md5Hex(std::string_view bytes);

/// md5sum of PoseGraphNode, PoseGraphEdge and PoseGraph by the rule above.
std::string poseGraphNodeMd5();
std::string poseGraphEdgeMd5();
std::string poseGraphMd5();

/// The full message definition a bag's connection header carries for PoseGraph (as gencpp composes it: the
/// message's text, then each dependency once, depth first, after a line of 80 '=' and "MSG: <type>").
/// `header_text`, `pose_text`, `point_text`, `quaternion_text` are the standard types' texts.
std::string poseGraphFullDefinition(std::string_view header_text, std::string_view pose_text,
                                    std::string_view point_text, std::string_view quaternion_text);

}  // namespace cosmo::nebula
