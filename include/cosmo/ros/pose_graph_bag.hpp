#pragma once
// pose_graph_msgs/PoseGraph messages in ROS 1 bags, without the pose_graph_msgs package: the bag container is
// read with Debian's rosbag library, each message's raw bytes are decoded by nebula::decodePoseGraph. The
// connection's type must be pose_graph_msgs/PoseGraph; an md5sum other than the definition's
// (nebula::poseGraphMd5()) is reported, and a message that then fails to decode names both md5sums.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cosmo/nebula/graph_builder.hpp"
#include "cosmo/nebula/pose_graph_msg.hpp"

namespace rosbag {
class Bag;
}

namespace cosmo::ros_glue {

/// The robot namespace of a "/<robot>/lamp/pose_graph_incremental" topic, "" for any other topic.
std::string poseGraphTopicRobot(const std::string& topic);

/// What was read from one topic of one bag.
struct PoseGraphTopicSummary {
  std::string bag, topic, robot, md5sum;
  std::size_t messages = 0;
  bool md5_matches = true;
};

/// Feeds every message of every /<robot>/lamp/pose_graph_incremental topic of `bag_path` (in bag time order)
/// to `builder`, the source of each named "<source_name> <topic> #<n>". Throws std::runtime_error naming bag,
/// topic and message when the bag cannot be read, a topic has another type, or a message does not decode.
std::vector<PoseGraphTopicSummary> readPoseGraphBag(
    const std::string& bag_path, const std::string& source_name, nebula::GraphBuilder& builder,
    nebula::CovarianceOrder order = nebula::CovarianceOrder::TranslationFirst);

/// Writes PoseGraph messages as pose_graph_msgs/PoseGraph (its full definition and md5sum in the connection
/// header), received at their header stamps. `md5sum` overrides the md5sum written (to make a mismatching bag).
class PoseGraphBagWriter {
 public:
  explicit PoseGraphBagWriter(const std::string& bag_path, std::string md5sum = "");
  ~PoseGraphBagWriter();
  void write(const std::string& topic, const nebula::PoseGraph& graph);
  /// Raw bytes as one message (e.g. a truncated one), received at `stamp`.
  void writeBytes(const std::string& topic, StampNs stamp, const std::vector<std::uint8_t>& bytes);
  void close();

 private:
  std::unique_ptr<rosbag::Bag> bag_;
  std::string md5sum_, definition_;
};

}  // namespace cosmo::ros_glue
