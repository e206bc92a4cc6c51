#pragma once
// Absolute trajectory error of a team's pose estimate against the ground truth, without alignment (COSMO
// datasets anchor every robot with a prior in the ground-truth frame, so the frames already agree). Per robot
// over its own poses (teammates' keys excluded), as jrl.md §13 defines the pose error: E = gt^-1 * est,
// translation error |t_E| (= |t_est - t_gt|), rotation error = angle of E.
#include <cstddef>
#include <map>
#include <vector>

#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::jrl {

struct PoseErrorRmse {
  double trans_m = 0.0;  ///< sqrt(mean |t_E|^2)
  double rot_rad = 0.0;  ///< sqrt(mean angle(E)^2)
  std::size_t poses = 0;
};

struct TrajectoryError {
  std::map<char, PoseErrorRmse> robots;
  PoseErrorRmse overall;  ///< RMSE over every robot's own poses pooled
};

/// ATE of `estimate` over the own poses of `robots` that `groundtruth` holds. Throws std::runtime_error naming
/// the first ground-truth key missing from `estimate`.
TrajectoryError trajectoryError(const std::vector<char>& robots, const PoseMap& estimate, const PoseMap& groundtruth);

}  // namespace cosmo::jrl
