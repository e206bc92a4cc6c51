#pragma once
// Local refinement after the global solve: point-to-plane ICP (Gauss-Newton on SE(3)) between the
// downsampled source points and the downsampled target points with normals, nearest neighbours by an exact
// kd-tree; and the overlap measure of the gate. Deterministic.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "cosmo/common/kd_tree.hpp"

namespace cosmo::registration {

struct IcpResult {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  int iterations = 0;
  std::size_t matched = 0;  ///< source points with a target neighbour within max_distance at the end
  double rmse = 0.0;        ///< point-to-plane RMSE over those
  bool converged = false;
};

IcpResult refinePointToPlane(const std::vector<Eigen::Vector3f>& source, const std::vector<Eigen::Vector3f>& target,
                             const std::vector<Eigen::Vector3f>& target_normals, const Eigen::Isometry3d& initial,
                             double max_distance, int max_iterations);

/// The same against a kd-tree built over `target` (reused across several initial guesses).
IcpResult refinePointToPlane(const std::vector<Eigen::Vector3f>& source, const KdTree<3>& target_tree,
                             const std::vector<Eigen::Vector3f>& target,
                             const std::vector<Eigen::Vector3f>& target_normals, const Eigen::Isometry3d& initial,
                             double max_distance, int max_iterations);

/// Fraction of `source` points that have a target point within `max_distance` after applying T.
double overlapFraction(const std::vector<Eigen::Vector3f>& source, const KdTree<3>& target_tree,
                       const Eigen::Isometry3d& T, double max_distance);

/// overlapFraction() of `source` and, in the same pass, of its points flagged in `flagged` (one flag per point):
/// {fraction of all points, fraction of the flagged points} (0 for none), the same values as two separate calls.
struct Overlaps {
  double all = 0.0;
  double flagged = 0.0;
};
Overlaps overlapFractions(const std::vector<Eigen::Vector3f>& source, const std::vector<unsigned char>& flagged,
                          const KdTree<3>& target_tree, const Eigen::Isometry3d& T, double max_distance);

}  // namespace cosmo::registration
