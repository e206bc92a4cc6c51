#include "cosmo/ros/bag_io.hpp"

#include <ros/time.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/serialization.h>

#include <stdexcept>
#include <vector>

#include "cosmo/ros/point_cloud.hpp"

namespace cosmo::ros_glue {

namespace {
void initTime() {
  if (!ros::Time::isValid()) ros::Time::init();
}
}  // namespace

struct ScanBagReader::Impl {
  rosbag::Bag bag;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator it;
  std::string where;
  bool stamp_at_end = true;
  std::vector<uint8_t> buffer;  ///< the serialized message, reused (it only grows)
  sensor_msgs::PointCloud2 meta;  ///< everything but `data`, which is decoded from `buffer` in place
};

ScanBagReader::ScanBagReader(const std::string& bag_path, const std::string& topic, bool stamp_at_end)
    : impl_(std::make_unique<Impl>()) {
  initTime();
  impl_->where = bag_path + " " + topic;
  impl_->stamp_at_end = stamp_at_end;
  try {
    impl_->bag.open(bag_path, rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    throw std::runtime_error(bag_path + ": cannot open bag: " + e.what());
  }
  impl_->view = std::make_unique<rosbag::View>(impl_->bag, rosbag::TopicQuery(topic));
  if (impl_->view->size() == 0) throw std::runtime_error(impl_->where + ": no messages on this topic");
  impl_->it = impl_->view->begin();
}

ScanBagReader::~ScanBagReader() = default;

std::size_t ScanBagReader::size() const { return impl_->view->size(); }

bool ScanBagReader::next(Scan& scan) {
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
      decodePointCloud2(meta, data, bytes, impl_->stamp_at_end, impl_->where, scan);
    } catch (const ros::serialization::StreamOverrunException& e) {
      throw std::runtime_error(impl_->where + ": truncated PointCloud2 message: " + e.what());
    }
    return true;
  }
  return false;
}

ScanBagWriter::ScanBagWriter(const std::string& bag_path) : bag_(std::make_unique<rosbag::Bag>()), path_(bag_path) {
  initTime();
  try {
    bag_->open(bag_path, rosbag::bagmode::Write);
  } catch (const std::exception& e) {
    throw std::runtime_error(bag_path + ": cannot write bag: " + e.what());
  }
}

ScanBagWriter::~ScanBagWriter() { close(); }

void ScanBagWriter::write(const std::string& topic, const Scan& scan, const std::string& frame_id) {
  const auto msg = toPointCloud2(scan, frame_id);
  bag_->write(topic, msg.header.stamp, msg);
}

void ScanBagWriter::close() {
  if (bag_ && bag_->isOpen()) bag_->close();
}

}  // namespace cosmo::ros_glue
