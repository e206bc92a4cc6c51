#pragma once
// Scans in ROS 1 bags (no roscore needed). Errors throw std::runtime_error naming the bag and topic.
#include <memory>
#include <string>

#include "cosmo/common/scan.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"

namespace rosbag {
class Bag;
class View;
}  // namespace rosbag

namespace cosmo::ros_glue {

/// Reads the sensor_msgs/PointCloud2 messages of one topic in time order (decoded by trials::decodeCloud:
/// invalid returns dropped). The topic is found with or without its leading slash; when it is missing the
/// error lists the bag's topics.
class ScanBagReader {
 public:
  ScanBagReader(const std::string& bag_path, const std::string& topic, bool stamp_at_end = true);
  ~ScanBagReader();
  /// Number of messages on the topic.
  std::size_t size() const;
  /// Next scan (stamped with its header stamp); false at the end.
  bool next(Scan& scan);
  /// Layout and counts of the last message decoded by next().
  const trials::CloudLayout& lastLayout() const;
  trials::DecodeCounts lastCounts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Chunk compression of a written bag.
enum class BagCompression { None, Bz2, Lz4 };

/// Writes scans as sensor_msgs/PointCloud2 (fields x y z intensity t ring), received time = header stamp.
class ScanBagWriter {
 public:
  explicit ScanBagWriter(const std::string& bag_path, BagCompression compression = BagCompression::None);
  ~ScanBagWriter();
  void write(const std::string& topic, const Scan& scan, const std::string& frame_id);
  /// A cloud exactly as given (fields, organisation), received time = its header stamp.
  void write(const std::string& topic, const trials::RawCloud& cloud);
  void close();

 private:
  std::unique_ptr<rosbag::Bag> bag_;
  std::string path_;
};

}  // namespace cosmo::ros_glue
