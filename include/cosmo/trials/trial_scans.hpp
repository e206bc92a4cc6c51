#pragma once
// A trial's scans as a sequence::ScanSource, whatever the container: what every reader (ROS 1 bag, ROS 2 sqlite3
// bag) also tells about the messages it decoded, for pre-flight checks.
// Invalid returns are already dropped from the scans (trials::decodeCloud).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"
#include "cosmo/trials/ros1_message_stream.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"
#include "cosmo/trials/ros2_bag.hpp"

namespace cosmo::trials {

class TrialScanSource : public sequence::ScanSource {
 public:
  /// Number of messages on the topic.
  virtual std::size_t size() const = 0;
  /// Layout (fields, types, height x width) of the last message decoded by next().
  virtual const CloudLayout& lastLayout() const = 0;
  /// Points and invalid returns of the last message decoded by next().
  virtual DecodeCounts lastCounts() const = 0;
};

/// sensor_msgs/msg/PointCloud2 messages of a ROS 2 sqlite3 bag.
class Ros2ScanSource : public TrialScanSource {
 public:
  Ros2ScanSource(const std::string& bag_path, const std::string& topic, bool stamp_at_end = true);
  bool next(Scan& scan) override;
  std::size_t size() const override { return reader_.size(); }
  const CloudLayout& lastLayout() const override { return layout_; }
  DecodeCounts lastCounts() const override { return counts_; }

 private:
  Ros2BagReader reader_;
  bool stamp_at_end_;
  CloudLayout layout_;
  DecodeCounts counts_;
};

/// sensor_msgs/PointCloud2 or Livox CustomMsg messages of a ROS 1 bag (trials/ros1_bag.hpp, ros1_point_cloud.hpp),
/// read without ROS; the chunks are decompressed ahead on `threads` workers (negative: defaultChunkThreads).
/// Throws naming the bag and the topic when the topic is missing (listing the bag's topics), empty or not of a
/// cloud type (trials::ros1CloudType).
class Ros1ScanSource : public TrialScanSource {
 public:
  Ros1ScanSource(const std::string& bag_path, const std::string& topic, bool stamp_at_end = true, int threads = -1);
  bool next(Scan& scan) override;
  std::size_t size() const override { return stream_->size(); }
  const CloudLayout& lastLayout() const override { return layout_; }
  DecodeCounts lastCounts() const override { return counts_; }

 private:
  Ros1CloudType type_{};
  std::unique_ptr<Ros1MessageStream> stream_;
  std::string where_;
  bool stamp_at_end_;
  CloudLayout layout_;
  DecodeCounts counts_;
};

/// Header stamps of the first and the last cloud (PointCloud2 or Livox CustomMsg) of `topic` in a ROS 1 bag
/// (reads the first message and the messages received in the bag's last 5 s; header stamps may lag the receive
/// times).
sequence::TrialSpan readRos1TrialSpan(const std::string& bag_path, const std::string& topic, char robot);

/// Header stamps of the first and the last PointCloud2 of `topic` in a ROS 2 bag (reads the first message and
/// the messages received in the bag's last 5 s; header stamps may lag the receive times).
sequence::TrialSpan readRos2TrialSpan(const std::string& bag_path, const std::string& topic, char robot);

}  // namespace cosmo::trials
