#include "cosmo/ros/resolved_sequence.hpp"

#include <ros/param.h>

namespace cosmo::ros_glue {

std::optional<ResolvedSequence> resolvedSequence() {
  ResolvedSequence s;
  if (!ros::param::get(kResolvedSequenceParam, s.path) || s.path.empty()) return std::nullopt;
  ros::param::get(kResolvedDataRootParam, s.data_root);
  ros::param::get(kResolvedRegistrationParam, s.registration);
  return s;
}

void publishResolvedSequence(const std::string& path, unsigned long long seed, const std::string& data_root,
                             const std::map<std::string, std::string>& registration) {
  ros::param::set(kResolvedSeedParam, std::to_string(seed));
  ros::param::set(kResolvedDataRootParam, data_root);
  if (registration.empty())
    ros::param::del(kResolvedRegistrationParam);  // none left from an earlier sequence on this master
  else
    ros::param::set(kResolvedRegistrationParam, registration);
  ros::param::set(kResolvedSequenceParam, path);
}

}  // namespace cosmo::ros_glue
