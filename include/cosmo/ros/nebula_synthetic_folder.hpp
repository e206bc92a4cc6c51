#pragma once
// A synthetic team (nebula/synthetic_team.hpp) written as a Nebula dataset folder in the distributed layout:
//   rosbag/<robot>.bag            /<robot>/lamp/pose_graph_incremental, pose_graph_msgs/PoseGraph
//   g2o_pcd/<robot>.g2o           the robot's graph (reference poses as vertices, its odometry and closures)
//   ground_truth/result.g2o       the reference solution (robot poses, artifacts, UWB anchors)
#include <string>

#include "cosmo/nebula/synthetic_team.hpp"

namespace cosmo::ros_glue {

/// Creates the folders as needed; throws std::runtime_error naming the file on I/O failure.
void writeNebulaFolder(const std::string& dir, const nebula::SyntheticTeam& team);

}  // namespace cosmo::ros_glue
