#pragma once
// Surface normals and FPFH descriptors (Rusu et al. 2009) of a downsampled cloud. Implemented with PCL's
// NormalEstimation / FPFHEstimation (single-threaded, exact kd-tree search: deterministic); the PCL templates
// stay in point_features.cpp.
#include <Eigen/Core>
#include <vector>

namespace cosmo::registration {

constexpr int kFpfhDim = 33;
using FpfhMatrix = Eigen::Matrix<float, kFpfhDim, Eigen::Dynamic>;

/// Unit normals oriented towards the sensor at the origin; `valid[i]` is false where the neighbourhood
/// within `radius` has fewer than `min_neighbors` points (normal then zero).
struct PointNormals {
  std::vector<Eigen::Vector3f> normals;
  std::vector<bool> valid;
};
PointNormals estimateNormals(const std::vector<Eigen::Vector3f>& points, double radius, std::size_t min_neighbors);

/// FPFH of every point (column i for point i) over neighbours within `radius`; points and normals must be
/// valid (filter them first). A point without neighbours gets an all-zero column.
FpfhMatrix computeFpfh(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                       double radius);

}  // namespace cosmo::registration
