#pragma once
// Own normals + FPFH ("fast" backend): every neighbour pair within max(normal, SPFH, FPFH radius) found once on
// a hash grid (neighbour_pairs.hpp) and reused for the normal moments, the linearity test, the SPFH (pair
// feature computed once per pair, in vectorised blocks) and the FPFH sums; FPFH only at keypoints (one per
// keypoint voxel):
// FPFH(p) = SPFH(p) + 1/k sum_k SPFH(q_k) / |p - q_k| over q_k within fpfh_radius (Rusu et al. 2009), each of
// the three 11-bin sub-histograms normalised to 100 (PCL's layout and pair-feature definition). Faster than
// PCL because the SPFH radius is smaller than the FPFH radius and only keypoints get the weighted sum.
// Deterministic.
#include <Eigen/Core>
#include <vector>

#include "cosmo/registration/point_features.hpp"

namespace cosmo::registration {

struct FastFeatureParams {
  double normal_radius = 0.9;
  double fpfh_radius = 1.5;       ///< radius of the neighbours whose SPFH are averaged into a keypoint's FPFH
  double spfh_radius = 0.9;       ///< radius of each point's own SPFH (0 = fpfh_radius, PCL's choice)
  std::size_t min_neighbors = 5;  ///< within normal_radius, including the point
  double max_linearity = 0.99;    ///< (l1 - l2) / l1 of the covariance eigenvalues; above: dropped
  double keypoint_voxel = 0.0;    ///< FPFH only for one valid point per voxel of this size (0 = every point)
};

struct FastFeatures {
  std::vector<int> kept;                 ///< indices into the input of points with a valid normal
  std::vector<Eigen::Vector3f> normals;  ///< per kept point, oriented towards the origin
  std::vector<int> keypoints;            ///< indices into `kept` of the points with a feature
  FpfhMatrix features;                   ///< 33 x keypoints.size()
};

class StageObserver;

/// The observer (optional) is told when each sub-stage ends: "neighbours", "normals", "spfh", "fpfh".
FastFeatures computeFastFeatures(const std::vector<Eigen::Vector3f>& points, const FastFeatureParams& params,
                                 StageObserver* observer = nullptr);

}  // namespace cosmo::registration
