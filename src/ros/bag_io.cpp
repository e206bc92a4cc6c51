#include "cosmo/ros/bag_io.hpp"

#include <ros/time.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <stdexcept>

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
    auto msg = m.instantiate<sensor_msgs::PointCloud2>();
    if (!msg) throw std::runtime_error(impl_->where + ": message type " + m.getDataType() + " is not sensor_msgs/PointCloud2");
    scan = fromPointCloud2(*msg, impl_->stamp_at_end, impl_->where);
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
