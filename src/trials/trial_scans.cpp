#include "cosmo/trials/trial_scans.hpp"

#include <algorithm>
#include <stdexcept>

#include "cosmo/trials/cdr_point_cloud.hpp"

namespace cosmo::trials {

namespace {
constexpr const char* kPointCloud2 = "sensor_msgs/msg/PointCloud2";

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
  const CdrCloudView view = parseCdrPointCloud2(m.data, m.size, reader_.where());
  layout_ = view.layout;
  counts_ = decodeCloud(view.layout, view.data, view.bytes, stamp_at_end_, reader_.where(), scan);
  return true;
}

pipeline::TrialSpan readRos2TrialSpan(const std::string& bag_path, const std::string& topic, char robot) {
  Ros2BagReader reader(bag_path, topic);
  checkType(reader);
  auto stampOf = [&](const Ros2BagReader::Message& m) {
    return parseCdrPointCloud2(m.data, m.size, reader.where()).layout.stamp;
  };
  pipeline::TrialSpan span;
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
