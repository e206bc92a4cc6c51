#pragma once
// What every node's main does around its own steps: a fatal error ends the node with its message, and waits on
// other nodes poll a condition on wall time (the callbacks that make it true run on a spinner thread).
#include <cstdint>
#include <functional>
#include <string>

#include <ros/time.h>

namespace cosmo::ros_glue {

/// ros::init(argc, argv, name, options), its topics served where the node registers (loopback_alias.hpp: a
/// loopback-alias ROS_IP is logged and worked around).
void initNode(int& argc, char** argv, const std::string& name, std::uint32_t options = 0);

/// "master <ROS_MASTER_URI>, this node <its XML-RPC URI> (<where its address comes from>)": for a node that waits
/// for others, what a user checks on a multi-machine team (README "A robot per machine").
std::string whereThisNodeIs();

/// This process gets SIGINT when the process that started it (team_launcher, roslaunch) ends, so that a node never
/// outlives its launch; false when that parent already ended.
bool endWithParent();

/// Runs `body`: a std::exception it throws ends the node with ROS_FATAL "<name>: <what>"; returns the exit code.
int runNode(const char* name, const std::function<void()>& body);

/// Checks `done` every `period` s of wall time until it holds (true), or `deadline` passed or ROS shut down (false).
bool waitUntil(const std::function<bool()>& done, const ros::WallTime& deadline, double period = 0.05);

/// The wall time `seconds` from now.
ros::WallTime wallDeadline(double seconds);

}  // namespace cosmo::ros_glue
