#pragma once
// The nodes' rviz markers from the core's state: a front-end's map (frontend/frontend_map.hpp) and the radio's
// active links (comm/radio_status.hpp).
#include <map>
#include <string>
#include <utility>

#include <ros/time.h>
#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/MarkerArray.h>

#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/frontend/frontend_map.hpp"

namespace cosmo::ros_glue {

std_msgs::ColorRGBA colorMsg(float r, float g, float b, float a = 1.0f);
/// One colour per robot letter (six, repeating).
std_msgs::ColorRGBA robotColor(char robot);
/// Red rejected, green inlier, orange outlier, blue accepted without a label.
std_msgs::ColorRGBA closureLabelColor(frontend::ClosureLabel label);
/// Red (0) through yellow to green (1).
std_msgs::ColorRGBA throughputColor(double fraction);

/// A front-end's markers in `frame`: namespaces <r>/trajectory (line), <r>/keyframes (spheres) and
/// <r>/loop_closures (lines lifted above the trajectories, coloured by label). rviz flags an empty or one-point
/// line as an error: such a line is sent as DELETE until it has content.
visualization_msgs::MarkerArray frontendMarkers(const frontend::FrontendMap& map, char robot, const std::string& frame,
                                                const ros::Time& stamp);

/// The radio's `links` (of its latest steps, the latest at radio time `t`) as one line list in `frame`, each link
/// coloured by its mean throughput so far; DELETE when there are none.
visualization_msgs::MarkerArray linkMarkers(const comm::RadioSimulator& radio,
                                            const std::map<std::pair<char, char>, comm::ActiveCommunication>& links,
                                            double t, const std::string& frame, const ros::Time& stamp);

}  // namespace cosmo::ros_glue
