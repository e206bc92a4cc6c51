#pragma once
// LOAM feature extraction (Zhang & Singh 2014, Sec. V-A, as in COSMO-Bench's LOAM): per scan line, the
// unnormalised curvature c_i = || sum_{j=1..N} (X_{i-j} + X_{i+j}) - 2N X_i ||^2 (m^2); points near line ends
// or gaps, on the far side of occlusion boundaries, or on surfaces nearly parallel to the beam are invalid;
// each line is split into sectors and each sector gives up to M_e edge points (largest curvature above the
// edge threshold) and M_p planar points (smallest curvature below the planar threshold), picking a point
// invalidating its N neighbours on each side.
#include <Eigen/Core>
#include <vector>

#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/odometry/scan_lines.hpp"

namespace cosmo::odometry {

struct LoamFeatures {
  std::vector<Eigen::Vector3d> edge_points;    ///< sensor frame
  std::vector<Eigen::Vector3d> planar_points;  ///< sensor frame
  std::vector<float> edge_time;                ///< per-point time (s, relative to stamp); empty without times
  std::vector<float> planar_time;
  std::size_t size() const { return edge_points.size() + planar_points.size(); }
};

/// Validity of each point of one line for feature selection (the LOAM invalid-point rules).
std::vector<std::uint8_t> computeValidPoints(const ScanLine& line, const LoamParams& params);
/// Curvature of each point of one line; -1 where it is undefined (near line ends / gaps).
std::vector<float> computeCurvature(const ScanLine& line, const LoamParams& params);
/// Edge and planar features of all lines.
LoamFeatures extractFeatures(const ScanLines& lines, const LoamParams& params);
/// Keeps one planar feature per voxel of `voxel_size` m (0: all), with its time (LOAM's "less flat" filter).
void thinPlanarFeatures(LoamFeatures& features, double voxel_size);

}  // namespace cosmo::odometry
