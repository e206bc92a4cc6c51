#pragma once
// A scan prepared for global registration: downsampled points, normals and FPFH features. Computing it is
// the per-scan half of the work, so a loop-closure front-end can cache it per keyframe and register many
// pairs against it.
#include <Eigen/Core>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/registration/point_features.hpp"
#include "cosmo/registration/registration_params.hpp"

namespace cosmo::registration {

struct FeatureCloud {
  std::vector<Eigen::Vector3f> points;   ///< downsampled points that have a valid normal (used by the ICP)
  std::vector<Eigen::Vector3f> normals;  ///< their unit normals
  std::vector<int> keypoints;            ///< indices into `points` of the points that carry a feature
  FpfhMatrix features;                   ///< 33 x keypoints.size()
  std::size_t input_points = 0;          ///< points of the scan before downsampling
  std::size_t downsampled_points = 0;    ///< points after downsampling (before the normal filter)
};

class StageObserver;

/// Downsample, estimate normals, drop points without a normal, compute FPFH. The observer (optional) is told
/// when each stage ends ("downsample", then "neighbours", "normals", "spfh", "fpfh" for the fast backend or
/// "normals", "fpfh" for PCL's).
FeatureCloud computeFeatureCloud(const Scan& scan, const RegistrationParams& params, StageObserver* observer = nullptr);

}  // namespace cosmo::registration
