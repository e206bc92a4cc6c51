#include "cosmo/ros/pose_graph_bag.hpp"

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <ros/time.h>
#include <rosbag/bag.h>
#include <std_msgs/Header.h>

#include <regex>
#include <set>
#include <stdexcept>

#include "cosmo/nebula/message_definition.hpp"
#include "cosmo/nebula/ros1_serialization.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros1_message_stream.hpp"

namespace cosmo::ros_glue {

/// Serialized bytes with the connection data they are written under (rosbag writes any type with traits).
struct RawPoseGraph {
  const std::vector<std::uint8_t>* bytes = nullptr;
  const std::string* md5sum = nullptr;
  const std::string* definition = nullptr;
};

}  // namespace cosmo::ros_glue

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<cosmo::ros_glue::RawPoseGraph> {
  static const char* value(const cosmo::ros_glue::RawPoseGraph& m) { return m.md5sum->c_str(); }
};
template <>
struct DataType<cosmo::ros_glue::RawPoseGraph> {
  static const char* value(const cosmo::ros_glue::RawPoseGraph&) { return cosmo::nebula::kPoseGraphType; }
};
template <>
struct Definition<cosmo::ros_glue::RawPoseGraph> {
  static const char* value(const cosmo::ros_glue::RawPoseGraph& m) { return m.definition->c_str(); }
};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<cosmo::ros_glue::RawPoseGraph> {
  template <typename Stream>
  inline static void write(Stream& stream, const cosmo::ros_glue::RawPoseGraph& m) {
    std::memcpy(stream.advance(static_cast<uint32_t>(m.bytes->size())), m.bytes->data(), m.bytes->size());
  }
  inline static uint32_t serializedLength(const cosmo::ros_glue::RawPoseGraph& m) {
    return static_cast<uint32_t>(m.bytes->size());
  }
};
}  // namespace serialization
}  // namespace ros

namespace cosmo::ros_glue {

namespace {

void initTime() {
  if (!ros::Time::isValid()) ros::Time::init();
}

/// The text of a standard message alone (its generated definition without the appended dependencies).
std::string ownText(const std::string& definition) {
  const std::size_t sep = definition.find("\n" + std::string(80, '='));
  return sep == std::string::npos ? definition : definition.substr(0, sep + 1);
}

}  // namespace

std::string poseGraphTopicRobot(const std::string& topic) {
  static const std::regex pattern("^/([^/]+)/lamp/pose_graph_incremental$");
  std::smatch m;
  return std::regex_match(topic, m, pattern) ? m[1].str() : std::string();
}

std::vector<PoseGraphTopicSummary> readPoseGraphBag(const std::string& bag_path, const std::string& source_name,
                                                    nebula::GraphBuilder& builder, nebula::CovarianceOrder order) {
  auto bag = std::make_shared<const trials::Ros1Bag>(bag_path);  // throws naming the file, offset and record
  // 1. The pose-graph topics and their connections' type and md5sum.
  const std::string expected_md5 = nebula::poseGraphMd5();
  std::vector<PoseGraphTopicSummary> summaries;
  std::vector<std::uint32_t> ids;
  for (const trials::Ros1Connection& c : bag->connections()) {
    const std::string robot = poseGraphTopicRobot(c.topic);
    if (robot.empty()) continue;
    if (c.type != nebula::kPoseGraphType)
      throw std::runtime_error(bag_path + " " + c.topic + ": message type " + c.type + ", expected " +
                               nebula::kPoseGraphType);
    ids.push_back(c.id);
    bool known = false;
    for (auto& s : summaries) known |= s.topic == c.topic && s.md5sum == c.md5sum;
    if (!known) summaries.push_back({source_name, c.topic, robot, c.md5sum, 0, c.md5sum == expected_md5});
  }
  if (ids.empty()) return summaries;
  // 2. Every message, decoded from its raw bytes.
  trials::Ros1MessageStream stream(bag, bag->messages(ids), 0);
  trials::Ros1MessageRef m;
  trials::Ros1Bag::Bytes bytes;
  while (stream.next(m, bytes)) {
    const trials::Ros1Connection& c = bag->connection(m.connection);
    PoseGraphTopicSummary* summary = nullptr;
    for (auto& s : summaries)
      if (s.topic == c.topic && s.md5sum == c.md5sum) summary = &s;
    const std::string source = source_name + " " + c.topic + " #" + std::to_string(summary->messages++);
    nebula::PoseGraph graph;
    try {
      graph = nebula::decodePoseGraph(bytes.data, bytes.size);
    } catch (const nebula::DecodeError& e) {
      throw std::runtime_error(source + ": " + e.what() +
                               (summary->md5_matches ? std::string()
                                                     : " (the connection's md5sum " + summary->md5sum + " is not " +
                                                           nebula::kPoseGraphType + "'s " + expected_md5 +
                                                           ": the bag's message definition differs)"));
    }
    builder.addMessage(graph, summary->robot, source, order);
  }
  return summaries;
}

PoseGraphBagWriter::PoseGraphBagWriter(const std::string& bag_path, std::string md5sum)
    : bag_(std::make_unique<rosbag::Bag>()), md5sum_(md5sum.empty() ? nebula::poseGraphMd5() : std::move(md5sum)) {
  initTime();
  using namespace ros::message_traits;
  definition_ = nebula::poseGraphFullDefinition(
      Definition<std_msgs::Header>::value(), ownText(Definition<geometry_msgs::Pose>::value()),
      Definition<geometry_msgs::Point>::value(), Definition<geometry_msgs::Quaternion>::value());
  try {
    bag_->open(bag_path, rosbag::bagmode::Write);
  } catch (const std::exception& e) { throw std::runtime_error(bag_path + ": cannot write bag: " + e.what()); }
}

PoseGraphBagWriter::~PoseGraphBagWriter() { close(); }

void PoseGraphBagWriter::write(const std::string& topic, const nebula::PoseGraph& graph) {
  writeBytes(topic, graph.header.stampNs(), nebula::encodePoseGraph(graph));
}

void PoseGraphBagWriter::writeBytes(const std::string& topic, StampNs stamp, const std::vector<std::uint8_t>& bytes) {
  ros::Time t;
  t.fromNSec(stamp);
  if (t.isZero()) t = ros::TIME_MIN;  // rosbag refuses time zero
  bag_->write(topic, t, RawPoseGraph{&bytes, &md5sum_, &definition_});
}

void PoseGraphBagWriter::close() {
  if (bag_ && bag_->isOpen()) bag_->close();
}

}  // namespace cosmo::ros_glue
