#pragma once
// LOAM's local map: the edge and planar features of the last K registered scans, in the odometry frame,
// with one k-d tree over each kind, rebuilt per scan (KdTree3 builds ~25k points in a few ms): one tree over
// the K scans is searched once per query, where K per-scan trees would each be searched.
#include <deque>
#include <vector>

#include "cosmo/odometry/feature_extraction.hpp"
#include "cosmo/common/kd_tree3.hpp"

namespace cosmo::odometry {

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
  std::size_t numEdgePoints() const { return edge_tree_.size(); }
  std::size_t numPlanePoints() const { return plane_tree_.size(); }
  /// Up to k nearest map edge (planar) points within max_dist (m) of q, nearest first, into `out`.
  void nearestEdges(const Eigen::Vector3d& q, int k, double max_dist, std::vector<Eigen::Vector3d>& out) const;
  void nearestPlanes(const Eigen::Vector3d& q, int k, double max_dist, std::vector<Eigen::Vector3d>& out) const;
  const KdTree3& edgeTree() const { return edge_tree_; }
  const KdTree3& planeTree() const { return plane_tree_; }

 private:
  struct Entry {
    std::vector<Eigen::Vector3d> edges, planes;
  };
  std::size_t max_scans_;
  double edge_voxel_ = 0.0, planar_voxel_ = 0.0;
  std::deque<Entry> scans_;
  KdTree3 edge_tree_, plane_tree_;    ///< over the union of the scans (thinned when a voxel size is set)
  std::vector<std::uint32_t> order_;  ///< scratch: the build order handed to the trees
};

}  // namespace cosmo::odometry
