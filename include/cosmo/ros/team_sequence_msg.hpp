#pragma once
// The resolved sequence as the player hands it to the lockstep nodes over ROS (latched topics, so that the nodes
// read no bag or CSV and can run on other machines): cosmo/TeamSequence (/player/sequence) and one
// cosmo/ReferenceTrajectory per robot (/<r>/reference_trajectory), the poses bit-exact.
#include <string>

#include "cosmo/ReferenceTrajectory.h"
#include "cosmo/TeamSequence.h"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::ros_glue {

inline constexpr const char* kTeamSequenceTopic = "/player/sequence";
/// /<robot>/reference_trajectory
std::string referenceTrajectoryTopic(char robot);

cosmo::TeamSequence teamSequenceToMsg(const sequence::SequenceConfig& config, const sequence::SequenceTiming& timing);
cosmo::ReferenceTrajectory trajectoryToMsg(char robot, const Trajectory& trajectory, const std::string& frame_id);
/// Throws std::runtime_error naming `topic` and the field when the arrays disagree or the stamps do not increase.
Trajectory trajectoryFromMsg(const cosmo::ReferenceTrajectory& msg, const std::string& topic);

}  // namespace cosmo::ros_glue
