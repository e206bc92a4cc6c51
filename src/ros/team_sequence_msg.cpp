#include "cosmo/ros/team_sequence_msg.hpp"

#include <stdexcept>

#include "cosmo/ros/pose_msg.hpp"

namespace cosmo::ros_glue {

std::string referenceTrajectoryTopic(char robot) { return std::string("/") + robot + "/reference_trajectory"; }

cosmo::TeamSequence teamSequenceToMsg(const sequence::SequenceConfig& config, const sequence::SequenceTiming& timing) {
  cosmo::TeamSequence m;
  m.name = config.name;
  m.seed = config.seed;
  m.start = stampToRos(timing.start());
  m.end = stampToRos(timing.end());
  for (const auto& trial : config.trials) {
    const sequence::TrialTiming& t = timing.of(trial.robot);
    m.robots.push_back(trial.robot);
    m.trials.push_back(trial.name);
    m.first.push_back(stampToRos(t.start()));
    m.last.push_back(stampToRos(t.end()));
  }
  return m;
}

cosmo::ReferenceTrajectory trajectoryToMsg(char robot, const Trajectory& trajectory, const std::string& frame_id) {
  cosmo::ReferenceTrajectory m;
  m.header.frame_id = frame_id;
  m.robot = std::string(1, robot);
  m.stamps.reserve(trajectory.size());
  m.poses.reserve(12 * trajectory.size());
  for (const StampedPose& p : trajectory.poses()) {
    m.stamps.push_back(p.stamp);
    const std::vector<double> exact = poseToExact(p.pose);
    m.poses.insert(m.poses.end(), exact.begin(), exact.end());
  }
  return m;
}

Trajectory trajectoryFromMsg(const cosmo::ReferenceTrajectory& msg, const std::string& topic) {
  if (msg.poses.size() != 12 * msg.stamps.size())
    throw std::runtime_error(topic + ": poses holds " + std::to_string(msg.poses.size()) + " numbers for " +
                             std::to_string(msg.stamps.size()) + " stamps (12 per pose expected)");
  Trajectory t;
  const geometry_msgs::Pose unused;
  for (std::size_t i = 0; i < msg.stamps.size(); ++i) {
    if (i > 0 && msg.stamps[i] <= msg.stamps[i - 1])
      throw std::runtime_error(topic + ": stamps[" + std::to_string(i) + "] does not increase");
    const std::vector<double> exact(msg.poses.begin() + static_cast<long>(12 * i),
                                    msg.poses.begin() + static_cast<long>(12 * i + 12));
    t.append(msg.stamps[i], poseFromExactOrMsg(exact, unused));
  }
  return t;
}

}  // namespace cosmo::ros_glue
