#include "cosmo/ros/resolved_sequence.hpp"

#include <ros/param.h>

#include "cosmo/common/config_dir.hpp"

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

trials::SequenceChoice readSequenceChoice(const ros::NodeHandle& pnh) {
  trials::SequenceChoice c;
  int seed = -1;  // -1: the config's
  pnh.param("sequence", c.sequence, c.sequence);
  pnh.param("data_root", c.data_root, c.data_root);
  pnh.param("seed", seed, seed);
  if (seed >= 0) c.seed = static_cast<unsigned long long>(seed);
  pnh.param("max_seconds", c.max_seconds, c.max_seconds);
  pnh.param("simulate_config", c.simulate_config, c.simulate_config);
  pnh.param("simulate_out", c.simulate_out, c.simulate_out);
  pnh.param("noise_models", c.noise_models, c.noise_models);
  pnh.param("config_dir", c.config_dir, cosmo::defaultConfigDir());
  return c;
}

}  // namespace cosmo::ros_glue
