#include "cosmo/ros/bag_io.hpp"

#include <ros/time.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/serialization.h>
#include <topic_tools/shape_shifter.h>

#include <stdexcept>
#include <vector>

#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"

namespace cosmo::ros_glue {

namespace {
void initTime() {
  if (!ros::Time::isValid()) ros::Time::init();
}
}  // namespace

struct RosbagScanReader::Impl {
  rosbag::Bag bag;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator it;
  std::string where;
  bool stamp_at_end = true;
  std::vector<uint8_t> buffer;    ///< the serialized message, reused (it only grows)
  sensor_msgs::PointCloud2 meta;  ///< everything but `data`, which is decoded from `buffer` in place
  trials::CloudLayout layout;
  trials::DecodeCounts counts;
};

namespace {
std::string withoutSlash(const std::string& t) { return !t.empty() && t[0] == '/' ? t.substr(1) : t; }

/// The bag's spelling of `topic` (with or without a leading slash); throws listing the bag's topics.
std::string findTopic(rosbag::Bag& bag, const std::string& bag_path, const std::string& topic) {
  rosbag::View all(bag);
  std::string topics;
  for (const auto* c : all.getConnections()) {
    if (withoutSlash(c->topic) == withoutSlash(topic)) return c->topic;
    if (topics.find(c->topic + " (") == std::string::npos)
      topics += (topics.empty() ? "" : ", ") + c->topic + " (" + c->datatype + ")";
  }
  throw std::runtime_error(bag_path + ": no topic " + topic +
                           " in this ROS 1 bag; it has: " + (topics.empty() ? "none" : topics));
}
}  // namespace

RosbagScanReader::RosbagScanReader(const std::string& bag_path, const std::string& topic, bool stamp_at_end)
    : impl_(std::make_unique<Impl>()) {
  initTime();
  impl_->where = bag_path + " " + topic;
  impl_->stamp_at_end = stamp_at_end;
  try {
    impl_->bag.open(bag_path, rosbag::bagmode::Read);
  } catch (const std::exception& e) { throw std::runtime_error(bag_path + ": cannot open bag: " + e.what()); }
  impl_->view = std::make_unique<rosbag::View>(impl_->bag, rosbag::TopicQuery(findTopic(impl_->bag, bag_path, topic)));
  if (impl_->view->size() == 0) throw std::runtime_error(impl_->where + ": no messages on this topic");
  impl_->it = impl_->view->begin();
}

RosbagScanReader::~RosbagScanReader() = default;

std::size_t RosbagScanReader::size() const { return impl_->view->size(); }

bool RosbagScanReader::next(Scan& scan) {
  while (impl_->it != impl_->view->end()) {
    const rosbag::MessageInstance m = *impl_->it;  // a copy: the iterator's instance is reset by ++
    ++impl_->it;
    if (!m.isType<sensor_msgs::PointCloud2>())
      throw std::runtime_error(impl_->where + ": message type " + m.getDataType() + " is not sensor_msgs/PointCloud2");
    // The serialized message is copied once into a reused buffer and its point bytes decoded where they lie:
    // instantiate() would zero-fill a fresh ~1 MB vector and copy into it for every scan.
    const uint32_t size = m.size();
    if (impl_->buffer.size() < size) impl_->buffer.resize(size);
    try {
      ros::serialization::OStream out(impl_->buffer.data(), size);
      m.write(out);
      ros::serialization::IStream in(impl_->buffer.data(), size);
      sensor_msgs::PointCloud2& meta = impl_->meta;
      ros::serialization::deserialize(in, meta.header);
      ros::serialization::deserialize(in, meta.height);
      ros::serialization::deserialize(in, meta.width);
      ros::serialization::deserialize(in, meta.fields);
      ros::serialization::deserialize(in, meta.is_bigendian);
      ros::serialization::deserialize(in, meta.point_step);
      ros::serialization::deserialize(in, meta.row_step);
      uint32_t bytes = 0;
      ros::serialization::deserialize(in, bytes);
      const uint8_t* data = in.advance(bytes);
      ros::serialization::deserialize(in, meta.is_dense);
      impl_->counts = decodePointCloud2(meta, data, bytes, impl_->stamp_at_end, impl_->where, scan);
      impl_->layout.stamp = scan.stamp;
      impl_->layout.frame_id = meta.header.frame_id;
      impl_->layout.height = meta.height;
      impl_->layout.width = meta.width;
      impl_->layout.fields.clear();
      for (const auto& f : meta.fields) impl_->layout.fields.push_back({f.name, f.offset, f.datatype, f.count});
      impl_->layout.is_bigendian = meta.is_bigendian;
      impl_->layout.point_step = meta.point_step;
      impl_->layout.row_step = meta.row_step;
      impl_->layout.is_dense = meta.is_dense;
    } catch (const ros::serialization::StreamOverrunException& e) {
      throw std::runtime_error(impl_->where + ": truncated PointCloud2 message: " + e.what());
    }
    return true;
  }
  return false;
}

const trials::CloudLayout& RosbagScanReader::lastLayout() const { return impl_->layout; }
trials::DecodeCounts RosbagScanReader::lastCounts() const { return impl_->counts; }

ScanBagWriter::ScanBagWriter(const std::string& bag_path, BagCompression compression)
    : bag_(std::make_unique<rosbag::Bag>()), path_(bag_path) {
  initTime();
  try {
    bag_->open(bag_path, rosbag::bagmode::Write);
    if (compression == BagCompression::Bz2) bag_->setCompression(rosbag::compression::BZ2);
    if (compression == BagCompression::Lz4) bag_->setCompression(rosbag::compression::LZ4);
  } catch (const std::exception& e) { throw std::runtime_error(bag_path + ": cannot write bag: " + e.what()); }
}

ScanBagWriter::~ScanBagWriter() { close(); }

void ScanBagWriter::write(const std::string& topic, const Scan& scan, const std::string& frame_id) {
  const auto msg = toPointCloud2(scan, frame_id);
  bag_->write(topic, msg.header.stamp, msg);
}

void ScanBagWriter::write(const std::string& topic, const trials::RawCloud& cloud) {
  const auto msg = toPointCloud2(cloud);
  bag_->write(topic, msg.header.stamp, msg);
}

void ScanBagWriter::write(const std::string& topic, const Scan& scan, const std::string& frame_id,
                          trials::PointLayout layout) {
  if (layout == trials::PointLayout::Ouster) return write(topic, scan, frame_id);
  if (layout == trials::PointLayout::LivoxCustom)
    return writeSerialized(topic, scan.stamp, "livox_ros_driver/CustomMsg", trials::kLivoxCustomMsgMd5,
                           trials::kLivoxCustomMsgDefinition, trials::serializeLivoxCustomMsg(scan, frame_id));
  write(topic, trials::pointLayoutCloud(scan, layout, frame_id));
}

void ScanBagWriter::writeSerialized(const std::string& topic, StampNs received, const std::string& type,
                                    const std::string& md5sum, const std::string& definition,
                                    const std::vector<std::uint8_t>& bytes) {
  topic_tools::ShapeShifter message;
  message.morph(md5sum, type, definition, "");
  ros::serialization::IStream in(const_cast<std::uint8_t*>(bytes.data()), static_cast<uint32_t>(bytes.size()));
  message.read(in);
  ros::Time t;
  t.fromNSec(received);
  bag_->write(topic, t, message);
}

void ScanBagWriter::close() {
  if (bag_ && bag_->isOpen()) bag_->close();
}

}  // namespace cosmo::ros_glue
