#pragma once
// k-nearest-neighbour search over a fixed set of 3D points (nanoflann behind a small interface, so that its
// templates stay in one translation unit).
#include <Eigen/Core>
#include <memory>
#include <vector>

namespace cosmo {

class KdTree3 {
 public:
  KdTree3();
  ~KdTree3();
  KdTree3(KdTree3&&) noexcept;
  KdTree3& operator=(KdTree3&&) noexcept;

  /// Rebuilds the index over `points` (copied).
  void build(const std::vector<Eigen::Vector3d>& points);
  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3d& point(std::size_t i) const { return points_[i]; }
  /// Up to k nearest points within max_dist (m) of `query`, nearest first: their indices into `indices`.
  void knn(const Eigen::Vector3d& query, int k, double max_dist, std::vector<std::size_t>& indices) const;

 private:
  struct Index;
  std::vector<Eigen::Vector3d> points_;
  std::vector<float> coords_;  ///< x y z per point, for the index
  std::unique_ptr<Index> index_;
};

}  // namespace cosmo
