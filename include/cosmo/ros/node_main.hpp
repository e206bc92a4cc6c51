#pragma once
// What every node's main does around its own steps: a fatal error ends the node with its message, and waits on
// other nodes poll a condition on wall time (the callbacks that make it true run on a spinner thread).
#include <functional>

#include <ros/time.h>

namespace cosmo::ros_glue {

/// Runs `body`: a std::exception it throws ends the node with ROS_FATAL "<name>: <what>"; returns the exit code.
int runNode(const char* name, const std::function<void()>& body);

/// Checks `done` every `period` s of wall time until it holds (true), or `deadline` passed or ROS shut down (false).
bool waitUntil(const std::function<bool()>& done, const ros::WallTime& deadline, double period = 0.05);

/// The wall time `seconds` from now.
ros::WallTime wallDeadline(double seconds);

}  // namespace cosmo::ros_glue
