#pragma once
// LOAM's local map: the edge and planar features of the last K registered scans, in the odometry frame,
// with a k-d tree over each kind.
#include <deque>
#include <vector>

#include "cosmo/odometry/feature_extraction.hpp"
#include "cosmo/odometry/kd_tree.hpp"

namespace cosmo {

class LocalFeatureMap {
 public:
  /// `edge_voxel` / `planar_voxel` (m, 0 = off): the union of the scans is thinned to one point per voxel, the
  /// newest scan's point winning.
  explicit LocalFeatureMap(std::size_t max_scans = 3, double edge_voxel = 0.0, double planar_voxel = 0.0)
      : max_scans_(max_scans), edge_voxel_(edge_voxel), planar_voxel_(planar_voxel) {}
  /// Adds one scan's features (already in the odometry frame), drops the oldest beyond K, rebuilds the trees.
  void add(std::vector<Eigen::Vector3d> edges, std::vector<Eigen::Vector3d> planes);
  void clear();
  bool empty() const { return scans_.empty(); }
  std::size_t numScans() const { return scans_.size(); }
  const KdTree3& edges() const { return edge_tree_; }
  const KdTree3& planes() const { return plane_tree_; }

 private:
  struct Entry {
    std::vector<Eigen::Vector3d> edges, planes;
  };
  std::size_t max_scans_;
  double edge_voxel_ = 0.0, planar_voxel_ = 0.0;
  std::deque<Entry> scans_;
  KdTree3 edge_tree_, plane_tree_;
};

}  // namespace cosmo
