#include "cosmo/ros/bag_scan_source.hpp"

#include <ros/time.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <stdexcept>

#include "cosmo/pipeline/sequence_references.hpp"
#include "cosmo/pipeline/trial_coverage.hpp"
#include "cosmo/ros/point_cloud.hpp"

namespace cosmo::ros_glue {

pipeline::TrialSpan readTrialSpan(const std::string& bag_path, const std::string& topic, char robot,
                                  bool stamp_at_end) {
  if (!ros::Time::isValid()) ros::Time::init();
  rosbag::Bag bag;
  try {
    bag.open(bag_path, rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    throw std::runtime_error(bag_path + ": cannot open bag: " + e.what());
  }
  rosbag::View all(bag, rosbag::TopicQuery(topic));
  if (all.size() == 0) throw std::runtime_error(bag_path + " " + topic + ": no messages on this topic");
  auto stampOf = [&](const rosbag::MessageInstance& m) {
    auto msg = m.instantiate<sensor_msgs::PointCloud2>();
    if (!msg)
      throw std::runtime_error(bag_path + " " + topic + ": message type " + m.getDataType() +
                               " is not sensor_msgs/PointCloud2");
    if (stamp_at_end) return static_cast<StampNs>(msg->header.stamp.toNSec());
    Scan scan = fromPointCloud2(*msg, false, bag_path + " " + topic);  // the sweep end: the latest point
    pipeline::stampAtSweepEnd(scan);
    return scan.stamp;
  };
  pipeline::TrialSpan span;
  span.robot = robot;
  span.first = stampOf(*all.begin());
  // The last header stamp: scan the messages received in the bag's last 5 s (header stamps may lag).
  const ros::Time end = all.getEndTime();
  const ros::Time from = end.toSec() > 5.0 ? end - ros::Duration(5.0) : ros::Time(0, 1);
  rosbag::View tail(bag, rosbag::TopicQuery(topic), from, end + ros::Duration(1.0));
  span.last = span.first;
  for (const auto& m : tail) span.last = std::max(span.last, stampOf(m));
  return span;
}

pipeline::SequenceTiming synchronizeSequence(const pipeline::SequenceConfig& config) {
  std::vector<pipeline::TrialSpan> spans;
  for (const auto& t : config.trials)
    spans.push_back(pipeline::trialCoverage(t).clip(readTrialSpan(t.bag, t.topic, t.robot, t.stamp_at_end)));
  return pipeline::SequenceTiming::synchronize(spans, config.anchor, config.time_offset_sigma, config.seed);
}

std::map<char, std::unique_ptr<pipeline::ScanSource>> openTrialSources(const pipeline::SequenceConfig& config) {
  std::map<char, std::unique_ptr<pipeline::ScanSource>> sources;
  for (const auto& t : config.trials)
    sources[t.robot] = std::make_unique<pipeline::CoveredScanSource>(
        std::make_unique<BagScanSource>(t.bag, t.topic, t.stamp_at_end), pipeline::trialCoverage(t));
  return sources;
}

pipeline::MergedScanStream openSequenceStream(const pipeline::SequenceConfig& config,
                                              const pipeline::SequenceTiming& timing) {
  return pipeline::MergedScanStream(openTrialSources(config), timing);
}

}  // namespace cosmo::ros_glue
