#pragma once
// How far a relative-pose measurement is from the ground truth, as the outlier labels measure it (jrl.md §10,
// spec section 6): E = m^-1 * m_gt with m_gt = gt(key1)^-1 * gt(key2), r = Log(E) rotation first, and the squared
// Mahalanobis distance d^2 = r^T Σ^-1 r under the factor's own covariance.
#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::jrl {

struct ClosureError {
  double trans_m = 0.0;  ///< |t_E|
  double rot_rad = 0.0;  ///< angle of E
  double d2 = 0.0;       ///< r^T Σ^-1 r; +Inf when Σ is not positive definite
};

/// Error of a between factor (or a prior, against gt(key1)). Throws std::runtime_error naming a key without
/// ground truth.
ClosureError closureError(const PoseFactor& factor, const PoseMap& groundtruth);

}  // namespace cosmo::jrl
