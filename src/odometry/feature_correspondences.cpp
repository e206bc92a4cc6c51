#include "cosmo/odometry/feature_correspondences.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace cosmo {
namespace {
void meanAndScatter(const std::vector<Eigen::Vector3d>& pts, Eigen::Vector3d& mean, Eigen::Matrix3d& scatter) {
  mean.setZero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  scatter.setZero();
  for (const auto& p : pts) {
    const Eigen::Vector3d d = p - mean;
    scatter += d * d.transpose();
  }
  scatter /= static_cast<double>(pts.size());
}
}  // namespace

std::optional<LinearConstraint> fitLineConstraint(const std::vector<Eigen::Vector3d>& nb, const Eigen::Vector3d& q,
                                                  const LoamParams& params) {
  if (static_cast<int>(nb.size()) < std::max(2, params.min_line_fit_points)) return std::nullopt;
  Eigen::Vector3d mean;
  Eigen::Matrix3d scatter;
  meanAndScatter(nb, mean, scatter);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(scatter);
  const Eigen::Vector3d ev = es.eigenvalues();  // ascending
  if (!(ev[2] > 0.0) || ev[2] < params.min_line_condition_number * std::max(ev[1], 1e-12)) return std::nullopt;
  const Eigen::Vector3d u = es.eigenvectors().col(2);
  const Eigen::Vector3d d = q - mean;
  Eigen::Vector3d w = d - u * u.dot(d);
  const double dist = w.norm();
  Eigen::Vector3d n;
  if (dist > 1e-9) {
    n = w / dist;
  } else {  // on the line: any perpendicular direction (residual 0)
    n = es.eigenvectors().col(1);
  }
  return LinearConstraint{n, n.dot(mean)};
}

std::optional<LinearConstraint> fitPlaneConstraint(const std::vector<Eigen::Vector3d>& nb, const LoamParams& params) {
  if (static_cast<int>(nb.size()) < std::max(3, params.min_plane_fit_points)) return std::nullopt;
  Eigen::Vector3d mean;
  Eigen::Matrix3d scatter;
  meanAndScatter(nb, mean, scatter);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(scatter);
  // Collinear neighbours (e.g. all on one scan line) do not define a plane.
  if (!(es.eigenvalues()[1] > params.min_plane_spread_ratio * es.eigenvalues()[2]) || !(es.eigenvalues()[1] > 1e-12))
    return std::nullopt;
  const Eigen::Vector3d n = es.eigenvectors().col(0).normalized();
  const double offset = n.dot(mean);
  double sum = 0.0;
  for (const auto& p : nb) sum += std::abs(n.dot(p) - offset);
  if (sum / static_cast<double>(nb.size()) > params.max_avg_point_plane_dist) return std::nullopt;
  return LinearConstraint{n, offset};
}

void associateFeatures(const std::vector<Eigen::Vector3d>& edges, const std::vector<Eigen::Vector3d>& planes,
                       const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                       std::vector<FeatureConstraint>& out, std::size_t stride) {
  out.clear();
  stride = std::max<std::size_t>(1, stride);
  std::vector<Eigen::Vector3d> nb;
  if (map.numEdgePoints() > 0) {
    for (std::size_t i = 0; i < edges.size(); i += stride) {
      const Eigen::Vector3d q = T * edges[i];
      map.nearestEdges(q, params.num_edge_neighbors, params.max_edge_neighbor_dist, nb);
      if (auto c = fitLineConstraint(nb, q, params)) out.push_back({edges[i], c->normal, c->offset, true, i, 1.0});
    }
  }
  if (map.numPlanePoints() > 0) {
    for (std::size_t i = 0; i < planes.size(); i += stride) {
      const Eigen::Vector3d q = T * planes[i];
      map.nearestPlanes(q, params.num_plane_neighbors, params.max_plane_neighbor_dist, nb);
      if (auto c = fitPlaneConstraint(nb, params)) out.push_back({planes[i], c->normal, c->offset, false, i, 1.0});
    }
  }
}

}  // namespace cosmo
