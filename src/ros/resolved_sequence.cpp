#include "cosmo/ros/resolved_sequence.hpp"

#include <ros/param.h>
#include <ros/rate.h>
#include <ros/time.h>

#include <stdexcept>

#include "cosmo/trials/trial_reference.hpp"
#include "cosmo/ros/bag_scan_source.hpp"

namespace cosmo::ros_glue {

Trajectory ResolvedSequence::reference(char robot) const {
  for (const auto& t : config.trials)
    if (t.robot == robot)
      return trials::loadSensorReference(t, timing.of(robot), trials::sequenceReferenceOffset(config));
  return {};
}

ResolvedSequence resolveSequence(const std::string& path, unsigned long long seed, const std::string& data_root) {
  ResolvedSequence r;
  r.config = pipeline::SequenceConfig::load(path, data_root);
  r.config.seed = seed;
  r.timing = synchronizeSequence(r.config);
  return r;
}

void publishResolvedSequence(const std::string& path, unsigned long long seed, const std::string& data_root) {
  ros::param::set(kResolvedSeedParam, std::to_string(seed));
  ros::param::set(kResolvedDataRootParam, data_root);
  ros::param::set(kResolvedSequenceParam, path);  // last: readers wait for this one
}

ResolvedSequence readResolvedSequence(double timeout_s) {
  const ros::WallTime start = ros::WallTime::now();
  std::string path, seed;
  while (!ros::param::get(kResolvedSequenceParam, path)) {
    if ((ros::WallTime::now() - start).toSec() > timeout_s)
      throw std::runtime_error(std::string("no parameter ") + kResolvedSequenceParam + " (is the player running?)");
    ros::WallDuration(0.05).sleep();
  }
  if (!ros::param::get(kResolvedSeedParam, seed)) throw std::runtime_error(std::string("no parameter ") + kResolvedSeedParam);
  std::string data_root;
  ros::param::get(kResolvedDataRootParam, data_root);
  return resolveSequence(path, std::stoull(seed), data_root);
}

}  // namespace cosmo::ros_glue
