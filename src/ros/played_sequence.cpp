#include "cosmo/ros/played_sequence.hpp"

#include <ros/console.h>

#include <filesystem>
#include <stdexcept>

#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_list.hpp"

namespace cosmo::ros_glue {

trials::ResolvedSequence resolvePlayedSequence(const trials::SequenceChoice& choice,
                                               const trials::TrialBases& trial_bases) {
  const auto announced = [&](const sequence::SequenceConfig& config) {
    std::vector<char> robots;
    for (const auto& t : config.trials) robots.push_back(t.robot);
    publishTeamRobots(robots);
    return trial_bases(config);
  };
  const auto say = [](const std::string& line) { ROS_INFO("player: %s", line.c_str()); };
  trials::ResolvedSequence s;
  try {
    s = trials::resolveSequence(choice, announced, say);
  } catch (const trials::PreflightFailed& failed) {
    ROS_INFO("player: pre-flight check:\n%s", failed.report.c_str());
    throw std::runtime_error("the pre-flight check failed (above)");
  }
  if (!s.check_report.empty()) ROS_INFO("player: pre-flight check:\n%s", s.check_report.c_str());
  if (s.noise) ROS_INFO("player: noise models %s", s.noise->describe().c_str());
  if (!s.config.registration.empty())
    ROS_INFO("player: the sequence's own registration keys apply (%s)", s.config.path.c_str());
  publishResolvedSequence(std::filesystem::absolute(s.config.path).string(), s.config.seed,
                          std::filesystem::absolute(s.config.data_root).string(), s.config.registration);
  return s;
}

}  // namespace cosmo::ros_glue
