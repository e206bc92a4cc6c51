#include "cosmo/ros/resolved_sequence.hpp"

#include <ros/param.h>

namespace cosmo::ros_glue {

void publishResolvedSequence(const std::string& path, unsigned long long seed, const std::string& data_root) {
  ros::param::set(kResolvedSeedParam, std::to_string(seed));
  ros::param::set(kResolvedDataRootParam, data_root);
  ros::param::set(kResolvedSequenceParam, path);
}

}  // namespace cosmo::ros_glue
