#include "cosmo/trials/trial_scans.hpp"

#include <algorithm>
#include <stdexcept>

#include "cosmo/trials/cdr_point_cloud.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"

namespace cosmo::trials {

namespace {
constexpr const char* kPointCloud2 = "sensor_msgs/msg/PointCloud2";
constexpr StampNs kSpanTail = 5000000000ULL;  ///< a trial's last stamp: from the messages of its last 5 s

/// The messages of `topic` (with or without its leading slash) of a ROS 1 bag, and their type (one for all its
/// connections); throws naming the bag and topic.
std::unique_ptr<Ros1MessageStream> openRos1Topic(const std::string& bag_path, const std::string& topic, int threads,
                                                 Ros1CloudType& type) {
  auto bag = std::make_shared<const Ros1Bag>(bag_path);
  const std::vector<std::uint32_t> ids = bag->topicConnections(topic);
  if (ids.empty())
    throw std::runtime_error(bag_path + ": no topic " + topic + " in this ROS 1 bag; it has: " + bag->describeTopics());
  const std::string where = bag_path + " " + topic;
  type = ros1CloudType(bag->connection(ids.front()), where);
  for (std::uint32_t id : ids)
    if (ros1CloudType(bag->connection(id), where) != type)
      throw std::runtime_error(where + ": connections of different message types (" +
                               bag->connection(ids.front()).type + ", " + bag->connection(id).type + ") on one topic");
  std::vector<Ros1MessageRef> messages = bag->messages(ids);
  if (messages.empty()) throw std::runtime_error(bag_path + " " + topic + ": no messages on this topic");
  const unsigned workers = threads < 0 ? defaultChunkThreads(*bag) : static_cast<unsigned>(threads);
  return std::make_unique<Ros1MessageStream>(std::move(bag), std::move(messages), workers);
}

void checkType(const Ros2BagReader& reader) {
  if (reader.topic().type != kPointCloud2)
    throw std::runtime_error(reader.where() + ": message type " + reader.topic().type + " is not " + kPointCloud2);
}
}  // namespace

Ros2ScanSource::Ros2ScanSource(const std::string& bag_path, const std::string& topic, bool stamp_at_end)
    : reader_(bag_path, topic), stamp_at_end_(stamp_at_end) {
  checkType(reader_);
}

bool Ros2ScanSource::next(Scan& scan) {
  Ros2BagReader::Message m;
  if (!reader_.next(m)) return false;
  const CloudView view = parseCdrPointCloud2(m.data, m.size, reader_.where());
  layout_ = view.layout;
  counts_ = decodeCloud(view.layout, view.data, view.bytes, stamp_at_end_, reader_.where(), scan);
  return true;
}

Ros1ScanSource::Ros1ScanSource(const std::string& bag_path, const std::string& topic, bool stamp_at_end, int threads)
    : stream_(openRos1Topic(bag_path, topic, threads, type_)),
      where_(bag_path + " " + topic),
      stamp_at_end_(stamp_at_end) {}

bool Ros1ScanSource::next(Scan& scan) {
  Ros1MessageRef m;
  Ros1Bag::Bytes bytes;
  if (!stream_->next(m, bytes)) return false;
  counts_ = decodeRos1Cloud(type_, bytes.data, bytes.size, stamp_at_end_, where_, scan, layout_);
  layout_.stamp = scan.stamp;
  return true;
}

sequence::TrialSpan readRos1TrialSpan(const std::string& bag_path, const std::string& topic, char robot) {
  Ros1CloudType type{};
  const std::unique_ptr<Ros1MessageStream> stream = openRos1Topic(bag_path, topic, 0, type);
  const std::string where = bag_path + " " + topic;
  Ros1MessageRef m;
  Ros1Bag::Bytes bytes;
  auto stampOf = [&]() { return parseRos1Cloud(type, bytes.data, bytes.size, where).layout.stamp; };
  sequence::TrialSpan span;
  span.robot = robot;
  stream->next(m, bytes);
  span.first = span.last = stampOf();
  // The messages received in the bag's last 5 s, as rosbag::View(start = end - 5 s) gives them.
  const StampNs end = stream->lastReceived();
  stream->seek(end > kSpanTail ? end - kSpanTail : 1);
  while (stream->next(m, bytes)) span.last = std::max(span.last, stampOf());
  return span;
}

sequence::TrialSpan readRos2TrialSpan(const std::string& bag_path, const std::string& topic, char robot) {
  Ros2BagReader reader(bag_path, topic);
  checkType(reader);
  auto stampOf = [&](const Ros2BagReader::Message& m) {
    return parseCdrPointCloud2(m.data, m.size, reader.where()).layout.stamp;
  };
  sequence::TrialSpan span;
  span.robot = robot;
  Ros2BagReader::Message m;
  if (!reader.next(m)) throw std::runtime_error(reader.where() + ": no messages on this topic");
  span.first = span.last = stampOf(m);
  const StampNs end = reader.lastReceived();
  const StampNs tail = 5000000000ULL;
  reader.seek(end > tail ? end - tail : 0);
  while (reader.next(m)) span.last = std::max(span.last, stampOf(m));
  return span;
}

}  // namespace cosmo::trials
