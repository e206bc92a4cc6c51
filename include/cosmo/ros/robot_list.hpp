#pragma once
// The ~robots parameter shared by the nodes: a list ([a, b, c]) or a string ("a,b,c", "a b c").
#include <ros/node_handle.h>

#include <string>
#include <vector>

namespace cosmo::ros_glue {

/// Robot ids from `~robots` of `pnh`; `fallback` (e.g. "a,b,c") when the parameter is absent, else the absence
/// throws. Throws std::runtime_error naming ~robots on a malformed entry or an empty list.
std::vector<char> readRobotsParam(const ros::NodeHandle& pnh, const std::string& fallback = "");

}  // namespace cosmo::ros_glue
