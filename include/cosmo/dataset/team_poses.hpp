#pragma once
// The team's poses and loop closures as outlier injection sees them (dataset/outlier_injection.hpp): per robot its
// own poses in index order, each with its ground truth and the entry that made it (the first entry of its owner
// that refers to it: the prior's or the odometry's), and every loop closure with its kind, covariance and
// measurement (intra- and inter-robot alike, as jrl::poseGraph() classifies them).
#include <cstddef>
#include <map>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::dataset {

struct TeamPose {
  jrl::Key key = 0;
  std::size_t entry = 0;  ///< the owner's entry that made the pose
  StampNs stamp = 0;      ///< that entry's stamp
  Pose3 truth = Pose3::Identity();
};

struct TeamPoses {
  std::map<char, std::vector<TeamPose>> robots;  ///< own poses with ground truth, in index order
  std::vector<jrl::PoseFactor> loop_closures;    ///< every loop closure of the dataset, in graph order

  /// Loop closures that are intra-robot (`inter` false) or inter-robot (`inter` true).
  std::vector<const jrl::PoseFactor*> closures(bool inter) const;
  /// Own poses of every robot.
  std::size_t poseCount() const;
};

/// The poses and loop closures of `graph`. Poses without ground truth or not referred to by their owner's own
/// entries are left out.
TeamPoses teamPoses(const jrl::PoseGraph& graph);

}  // namespace cosmo::dataset
