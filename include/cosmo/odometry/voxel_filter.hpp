#pragma once
// Voxel-grid thinning of a point list: the first point (in list order) of every occupied cubic voxel is kept.
// Deterministic (order-preserving); used to thin the local map and the planar features (LOAM's "less flat"
// downsampling).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace cosmo {

/// Indices (ascending) of the points kept: one per voxel of edge `voxel_size` (m). voxel_size <= 0: all.
std::vector<std::uint32_t> voxelFilterIndices(const std::vector<Eigen::Vector3d>& points, double voxel_size);

}  // namespace cosmo
