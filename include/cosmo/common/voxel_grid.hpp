#pragma once
// Voxel-grid reductions of a point list, two named ones for the two uses:
// - first point: the first point (in list order) of every occupied cubic voxel is kept, by index; deterministic
//   and order-preserving. LOAM thins its local map and its planar ("less flat") features so.
// - centroid: one point, the centroid, per occupied voxel, in a deterministic order (sorted by voxel key),
//   optionally dropping points outside [min_range, max_range] and non-finite points. Global registration
//   downsamples its clouds so.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace cosmo {

/// First point: indices (ascending) of the points kept, one per voxel of edge `voxel_size` (m). voxel_size <= 0:
/// all.
std::vector<std::uint32_t> voxelFilterIndices(const std::vector<Eigen::Vector3d>& points, double voxel_size);

/// Centroid: the centroid of each voxel of edge `voxel_size` (m), in voxel-key order; `max_range` 0: no limit.
std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                                             double min_range = 0.0, double max_range = 0.0);

}  // namespace cosmo
