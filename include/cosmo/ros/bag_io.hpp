#pragma once
// Scans in ROS 1 bags (no roscore needed). Errors throw std::runtime_error naming the bag and topic.
#include <memory>
#include <string>

#include "cosmo/common/scan.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"
#include "cosmo/trials/trial_scans.hpp"

namespace rosbag {
class Bag;
class View;
}  // namespace rosbag

namespace cosmo::ros_glue {

/// Reads the sensor_msgs/PointCloud2 messages of one topic in time order (decoded by trials::decodeCloud:
/// invalid returns dropped), through cosmo's own bounds-checked reader (trials::Ros1ScanSource): a damaged bag
/// throws naming the file, the byte offset and the record. The topic is found with or without its leading slash;
/// when it is missing the error lists the bag's topics.
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
  std::unique_ptr<trials::Ros1ScanSource> source_;
};

/// The same scans read through librosbag (rosbag::View), which does not check a bag's records (a damaged one can
/// crash it): kept only to check ScanBagReader against it (tests, bench_ros1_bag).
class RosbagScanReader {
 public:
  RosbagScanReader(const std::string& bag_path, const std::string& topic, bool stamp_at_end = true);
  ~RosbagScanReader();
  std::size_t size() const;
  bool next(Scan& scan);
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
