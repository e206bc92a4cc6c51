#pragma once
// A Nebula (LAMP 2.0) dataset folder as distributed (real_data_formats.md §4) converted to a JRL dataset:
//   <dir>/rosbag/**/*.bag          /<robot>/lamp/pose_graph_incremental (pose_graph_msgs/PoseGraph)
//   <dir>/g2o_pcd/**/*.g2o         the same graphs as g2o (read instead of the bags with from_g2o)
//   <dir>/ground_truth/result.g2o  the reference solution
// Reading is here (bags need rosbag); assembling is the ROS-free nebula module.
#include <string>
#include <vector>

#include "cosmo/jrl/dataset.hpp"
#include "cosmo/nebula/graph_builder.hpp"
#include "cosmo/nebula/jrl_assembly.hpp"
#include "cosmo/ros/pose_graph_bag.hpp"

namespace cosmo::ros_glue {

struct NebulaOptions {
  std::string dataset_dir;
  bool from_g2o = false;  ///< read g2o_pcd/ (no stamps: pose i of every robot is stamped i seconds)
  nebula::CovarianceOrder covariance_order = nebula::CovarianceOrder::TranslationFirst;
  nebula::ConversionParams params;
};

struct NebulaConversion {
  std::vector<std::string> inputs;            ///< files read, relative to the dataset folder
  std::vector<PoseGraphTopicSummary> topics;  ///< bag mode: per bag and topic
  std::size_t reference_poses = 0;            ///< vertices of result.g2o
  nebula::NebulaGraph graph;
  nebula::ConversionReport report;
  jrl::Dataset dataset;
};

/// Throws std::runtime_error naming the file (missing folder, no input, unreadable bag or g2o, a message
/// that does not decode) or the keys (nebula::GraphError, missing reference poses).
NebulaConversion convertNebulaDataset(const NebulaOptions& options);

}  // namespace cosmo::ros_glue
