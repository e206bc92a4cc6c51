#pragma once
// Scans in ROS 1 bags (no roscore needed). Errors throw std::runtime_error naming the bag and topic.
#include <memory>
#include <string>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"
#include "cosmo/trials/point_layouts.hpp"
#include "cosmo/trials/trial_scans.hpp"

namespace rosbag {
class Bag;
class View;
}  // namespace rosbag

namespace cosmo::ros_glue {

/// The scans of one topic read through librosbag (rosbag::View), which does not check a bag's records (a damaged
/// one can crash it): kept only to check cosmo's own reader (trials::Ros1ScanSource) against it (tests,
/// bench_ros1_bag).
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
  /// A scan in one of the point layouts LiDAR drivers publish (trials/point_layouts.hpp), received time = its
  /// stamp: a sensor_msgs/PointCloud2, or for livox-custom a livox_ros_driver/CustomMsg.
  void write(const std::string& topic, const Scan& scan, const std::string& frame_id, trials::PointLayout layout);
  /// A serialized message of any type (its name, md5sum and full definition as a connection record carries them).
  void writeSerialized(const std::string& topic, StampNs received, const std::string& type, const std::string& md5sum,
                       const std::string& definition, const std::vector<std::uint8_t>& bytes);
  void close();

 private:
  std::unique_ptr<rosbag::Bag> bag_;
  std::string path_;
};

}  // namespace cosmo::ros_glue
