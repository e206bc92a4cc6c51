#pragma once
// Voxel-grid downsampling: one point (the centroid) per occupied voxel, in a deterministic order (sorted by
// voxel key), optionally dropping points outside [min_range, max_range] and non-finite points.
#include <Eigen/Core>
#include <vector>

namespace cosmo {

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                                             double min_range = 0.0, double max_range = 0.0);

}  // namespace cosmo
