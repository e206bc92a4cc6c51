#include "cosmo/ros/trial_probe.hpp"

#include <ros/time.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>

#include <filesystem>
#include <set>

#include "cosmo/pipeline/sequence_references.hpp"
#include "cosmo/pipeline/trial_coverage.hpp"
#include "cosmo/ros/bag_scan_source.hpp"
#include "cosmo/ros/point_cloud.hpp"

namespace cosmo::ros_glue {

namespace {
const char* typeName(uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8: return "int8";
    case sensor_msgs::PointField::UINT8: return "uint8";
    case sensor_msgs::PointField::INT16: return "int16";
    case sensor_msgs::PointField::UINT16: return "uint16";
    case sensor_msgs::PointField::INT32: return "int32";
    case sensor_msgs::PointField::UINT32: return "uint32";
    case sensor_msgs::PointField::FLOAT32: return "float32";
    case sensor_msgs::PointField::FLOAT64: return "float64";
    default: return "unknown";
  }
}
}  // namespace

pipeline::TrialProbe probeTrial(const pipeline::TrialConfig& trial, std::size_t scans) {
  pipeline::TrialProbe probe;
  if (!std::filesystem::exists(trial.bag)) {
    probe.error = "bag not found: " + trial.bag;
    return probe;
  }
  if (!ros::Time::isValid()) ros::Time::init();
  rosbag::Bag bag;
  try {
    bag.open(trial.bag, rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    probe.error = trial.bag + ": cannot open bag: " + e.what();
    return probe;
  }
  probe.bag_found = true;
  rosbag::View all(bag);
  std::set<std::string> topics;
  for (const auto* c : all.getConnections()) topics.insert(c->topic + " (" + c->datatype + ")");
  probe.topics.assign(topics.begin(), topics.end());
  rosbag::View view(bag, rosbag::TopicQuery(trial.topic));
  probe.messages = view.size();
  if (probe.messages == 0) return probe;
  probe.topic_found = true;
  const std::string where = trial.bag + " " + trial.topic;
  try {
    for (const auto& m : view) {
      if (probe.first_scans.size() >= scans) break;
      auto msg = m.instantiate<sensor_msgs::PointCloud2>();
      if (!msg) throw std::runtime_error(where + ": message type " + m.getDataType() + " is not sensor_msgs/PointCloud2");
      if (probe.fields.empty())
        for (const auto& f : msg->fields)
          probe.fields += (probe.fields.empty() ? "" : " ") + f.name + ":" + typeName(f.datatype);
      probe.points_in_messages += static_cast<std::size_t>(msg->width) * msg->height;
      Scan scan = fromPointCloud2(*msg, trial.stamp_at_end, where);
      pipeline::stampAtSweepEnd(scan);
      probe.first_scans.push_back(std::move(scan));
    }
    probe.first_stamp = probe.first_scans.front().stamp;
    probe.last_stamp = readTrialSpan(trial.bag, trial.topic, trial.robot, trial.stamp_at_end).last;
  } catch (const std::exception& e) {
    probe.error = e.what();
  }
  return probe;
}

bool checkSequence(const pipeline::SequenceConfig& config, const std::string& noise_models, std::string& text) {
  std::vector<pipeline::TrialCheck> checks;
  for (const auto& t : config.trials) {
    Trajectory reference;
    std::string reference_error;
    try {
      if (!t.reference.empty() && !std::filesystem::exists(t.reference))
        reference_error = t.name + ": reference not found: " + t.reference;
      else
        reference = pipeline::readBodyReference(t);
    } catch (const std::exception& e) {
      reference_error = t.name + ": " + e.what();
    }
    checks.push_back(pipeline::checkTrial(t, probeTrial(t), reference, reference_error, noise_models));
  }
  const bool ok = pipeline::formatChecks(checks, text);
  std::string hint;
  for (const auto& c : checks)
    if (!ok && config.data_root_from == "config folder" && c.line.find("NOT FOUND") != std::string::npos)
      hint = "(the trials' paths are relative to the data root: give it with --data-root DIR / data_root:=DIR or "
             "COSMO_DATA_ROOT)\n";
  text = "sequence " + config.name + " (" + config.source + "), data root " + config.data_root + " (" +
         config.data_root_from + ")\n" + text + hint;
  return ok;
}

}  // namespace cosmo::ros_glue
