#pragma once
// The ~robots parameter shared by the nodes: a list ([a, b, c]) or a string ("a,b,c", "a b c").
#include <ros/node_handle.h>

#include <string>
#include <vector>

namespace cosmo::ros_glue {

/// Robot ids from `~robots` of `pnh`; `fallback` (e.g. "a,b,c") when the parameter is absent, else the absence
/// throws. Throws std::runtime_error naming ~robots on a malformed entry or an empty list.
std::vector<char> readRobotsParam(const ros::NodeHandle& pnh, const std::string& fallback = "");

/// A per-robot node's robot: ~robot, else its namespace (/<r>). Throws std::runtime_error unless one lower-case
/// letter.
char nodeRobot(const ros::NodeHandle& pnh);

/// The team's robots set by the player once it loaded the sequence config (a list of one-character strings).
inline constexpr const char* kTeamRobotsParam = "/player/robots";
/// Sets kTeamRobotsParam (the player).
void publishTeamRobots(const std::vector<char>& robots);
/// `~robots` of `pnh` when set; else the player's kTeamRobotsParam, waited for (as long as ROS runs: a built-in
/// sequence is generated first). Throws when ROS shuts down first or on a malformed list.
std::vector<char> readTeamRobots(const ros::NodeHandle& pnh);

}  // namespace cosmo::ros_glue
