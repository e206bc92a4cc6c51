#include "cosmo/odometry/feature_correspondences.hpp"

#include <algorithm>
#include <cmath>

#include "cosmo/odometry/symmetric_eigen3.hpp"

namespace cosmo::odometry {
namespace {
void meanAndScatter(const std::vector<Eigen::Vector3d>& pts, Eigen::Vector3d& mean, Eigen::Matrix3d& scatter) {
  double mx = 0.0, my = 0.0, mz = 0.0;
  for (const auto& p : pts) mx += p.x(), my += p.y(), mz += p.z();
  const double inv_n = 1.0 / static_cast<double>(pts.size());
  mx *= inv_n, my *= inv_n, mz *= inv_n;
  double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0, zz = 0.0;  // upper triangle, about the mean
  for (const auto& p : pts) {
    const double dx = p.x() - mx, dy = p.y() - my, dz = p.z() - mz;
    xx += dx * dx, xy += dx * dy, xz += dx * dz, yy += dy * dy, yz += dy * dz, zz += dz * dz;
  }
  mean = {mx, my, mz};
  scatter << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  scatter *= inv_n;
}

/// Whether one neighbour alone keeps `nb` (smallest-first eigenvalues `ev`) from being flat (see
/// LoamParams::plane_off_surface_min_dist).
bool oneNeighbourOffSurface(const std::vector<Eigen::Vector3d>& nb, const Eigen::Vector3d& ev,
                            const LoamParams& params) {
  const double d = params.plane_off_surface_min_dist;
  const double drop_factor = params.plane_off_surface_drop;
  if (nb.size() < static_cast<std::size_t>(params.plane_off_surface_min_neighbors) ||
      !(ev[0] > params.plane_off_surface_flatness * ev[1]) || !(ev[0] > d * d))
    return false;
  std::vector<Eigen::Vector3d> others;
  others.reserve(nb.size() - 1);
  Eigen::Vector3d mean;
  Eigen::Matrix3d scatter;
  for (std::size_t drop = 0; drop < nb.size(); ++drop) {
    others.clear();
    for (std::size_t j = 0; j < nb.size(); ++j)
      if (j != drop) others.push_back(nb[j]);
    meanAndScatter(others, mean, scatter);
    // Most drops leave the off-surface point in: their smallest eigenvalue stays large, which a lower bound
    // shows without the eigenvalues. lambda0 = det / (lambda1 lambda2) >= det / (trace / 2)^2; the margin
    // (1e-6 of the trace) is far above the rounding of the bound and of symmetricEigenvalues3, so a skipped
    // drop is one whose computed eigenvalue would have failed the test too.
    const double trace = scatter.trace();
    if (trace > 0.0 && 4.0 * scatter.determinant() / (trace * trace) >= drop_factor * ev[0] + 1e-6 * trace) continue;
    const Eigen::Vector3d e = symmetricEigenvalues3(scatter);
    if (e[1] > params.min_plane_spread_ratio * e[2] && e[0] < drop_factor * ev[0]) return true;
  }
  return false;
}
}  // namespace

std::optional<MapLine> fitMapLine(const std::vector<Eigen::Vector3d>& nb, const LoamParams& params) {
  if (static_cast<int>(nb.size()) < std::max(2, params.min_line_fit_points)) return std::nullopt;
  Eigen::Vector3d mean;
  Eigen::Matrix3d scatter;
  meanAndScatter(nb, mean, scatter);
  const Eigen::Vector3d ev = symmetricEigenvalues3(scatter);  // ascending
  if (!(ev[2] > 0.0) || ev[2] < params.min_line_condition_number * std::max(ev[1], 1e-12)) return std::nullopt;
  const Eigen::Vector3d u = symmetricEigenvector3(scatter, ev[2]);
  return MapLine{mean, u, anyPerpendicular(u)};
}

LinearConstraint lineConstraint(const MapLine& line, const Eigen::Vector3d& q) {
  const Eigen::Vector3d& u = line.direction;
  const Eigen::Vector3d d = q - line.mean;
  Eigen::Vector3d w = d - u * u.dot(d);
  const double dist = w.norm();
  Eigen::Vector3d n;
  if (dist > 1e-9) {
    n = w / dist;
  } else {  // on the line: any perpendicular direction (residual 0)
    n = line.normal_if_on_line;
  }
  return LinearConstraint{n, n.dot(line.mean)};
}

std::optional<LinearConstraint> fitLineConstraint(const std::vector<Eigen::Vector3d>& nb, const Eigen::Vector3d& q,
                                                  const LoamParams& params) {
  const std::optional<MapLine> line = fitMapLine(nb, params);
  if (!line) return std::nullopt;
  return lineConstraint(*line, q);
}

std::optional<LinearConstraint> fitPlaneConstraint(const std::vector<Eigen::Vector3d>& nb, const LoamParams& params) {
  if (static_cast<int>(nb.size()) < std::max(3, params.min_plane_fit_points)) return std::nullopt;
  Eigen::Vector3d mean;
  Eigen::Matrix3d scatter;
  meanAndScatter(nb, mean, scatter);
  const Eigen::Vector3d ev = symmetricEigenvalues3(scatter);  // ascending
  // Collinear neighbours (e.g. all on one scan line) do not define a plane.
  if (!(ev[1] > params.min_plane_spread_ratio * ev[2]) || !(ev[1] > 1e-12)) return std::nullopt;
  // Neighbours on two surfaces (see LoamParams::max_plane_planarity).
  if (params.max_plane_planarity > 0.0 && ev[0] > params.max_plane_planarity * ev[1]) return std::nullopt;
  // One neighbour off the others' surface (see LoamParams::plane_off_surface_min_dist).
  if (params.plane_off_surface_min_dist > 0.0 && oneNeighbourOffSurface(nb, ev, params)) return std::nullopt;
  const Eigen::Vector3d n = symmetricEigenvector3(scatter, ev[0]);
  const double offset = n.dot(mean);
  double sum = 0.0;
  for (const auto& p : nb) sum += std::abs(n.dot(p) - offset);
  if (sum / static_cast<double>(nb.size()) > params.max_avg_point_plane_dist) return std::nullopt;
  return LinearConstraint{n, offset};
}

void AssociationMemory::reset(std::size_t num_edges, std::size_t num_planes) {
  edges.assign(num_edges, Entry{});
  planes.assign(num_planes, Entry{});
  reused = searched = 0;
}

namespace {
/// Extra search distance (m) beyond the maximum neighbour distance, to bound how close the nearest point
/// outside the neighbour set is (it decides the reuse radius).
constexpr double kMemoryMargin = 0.1;
/// Slack (m) for the float distances of the tree (coordinates up to a few km).
constexpr double kMemorySlack = 1e-3;

/// The neighbours of q in `tree` (k nearest within max_dist, as KdTree3::search gives them, into `nb`) and the
/// radius around q within which a query keeps exactly this neighbour set.
double searchWithReuseRadius(const KdTree3& tree, const Eigen::Vector3d& q, int k, double max_dist,
                             std::vector<Eigen::Vector3d>& nb) {
  nb.clear();
  k = std::clamp(k, 0, KnnResult::kMaxK - 1);
  KnnResult result;
  result.reset(k + 1, max_dist + kMemoryMargin);
  tree.search(q, result);
  const float limit = static_cast<float>(max_dist * max_dist);  // as KnnResult::reset(k, max_dist) bounds it
  int m = 0;
  while (m < result.size() && m < k && result.squaredDistance(m) <= limit) {
    nb.push_back(tree.point(result.index(m)));
    ++m;
  }
  const double r_in = m > 0 ? std::sqrt(static_cast<double>(result.squaredDistance(m - 1))) : 0.0;
  const double r_out =
      m < result.size() ? std::sqrt(static_cast<double>(result.squaredDistance(m))) : max_dist + kMemoryMargin;
  // A shift d of the query moves every distance by at most d: the set stays while no member leaves the
  // max_dist ball and no outsider overtakes the k-th member (full set) or enters the ball (set not full).
  double radius = max_dist - r_in;
  radius = std::min(radius, m == k ? 0.5 * (r_out - r_in) : r_out - max_dist);
  return radius - kMemorySlack;
}
}  // namespace

void associateFeaturesRemembering(const std::vector<Eigen::Vector3d>& edges, const std::vector<Eigen::Vector3d>& planes,
                                  const LocalFeatureMap& map, const Pose3& T, const LoamParams& params,
                                  std::vector<FeatureConstraint>& out, AssociationMemory& memory,
                                  std::size_t memory_stride, bool remember) {
  out.clear();
  out.reserve(edges.size() + planes.size());
  memory_stride = std::max<std::size_t>(1, memory_stride);
  std::vector<Eigen::Vector3d> nb;
  if (map.numEdgePoints() > 0) {
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const Eigen::Vector3d q = T * edges[i];
      AssociationMemory::Entry& e = memory.edges[i * memory_stride];
      if (e.reuse_radius >= 0.0 && (q - e.query).squaredNorm() < e.reuse_radius * e.reuse_radius) {
        ++memory.reused;
        if (e.fitted) {
          const LinearConstraint c = lineConstraint(MapLine{e.a, e.b, e.c}, q);
          out.push_back({edges[i], c.normal, c.offset, true, i});
        }
        continue;
      }
      ++memory.searched;
      std::optional<MapLine> line;
      if (remember) {
        e.reuse_radius =
            searchWithReuseRadius(map.edgeTree(), q, params.num_edge_neighbors, params.max_edge_neighbor_dist, nb);
        e.query = q;
        line = fitMapLine(nb, params);
        e.fitted = line.has_value();
        if (line) e.a = line->mean, e.b = line->direction, e.c = line->normal_if_on_line;
      } else {
        map.nearestEdges(q, params.num_edge_neighbors, params.max_edge_neighbor_dist, nb);
        line = fitMapLine(nb, params);
      }
      if (line) {
        const LinearConstraint c = lineConstraint(*line, q);
        out.push_back({edges[i], c.normal, c.offset, true, i});
      }
    }
  }
  if (map.numPlanePoints() > 0) {
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const Eigen::Vector3d q = T * planes[i];
      AssociationMemory::Entry& e = memory.planes[i * memory_stride];
      if (e.reuse_radius >= 0.0 && (q - e.query).squaredNorm() < e.reuse_radius * e.reuse_radius) {
        ++memory.reused;
        if (e.fitted) out.push_back({planes[i], e.a, e.offset, false, i});
        continue;
      }
      ++memory.searched;
      std::optional<LinearConstraint> c;
      if (remember) {
        e.reuse_radius =
            searchWithReuseRadius(map.planeTree(), q, params.num_plane_neighbors, params.max_plane_neighbor_dist, nb);
        e.query = q;
        c = fitPlaneConstraint(nb, params);
        e.fitted = c.has_value();
        if (c) e.a = c->normal, e.offset = c->offset;
      } else {
        map.nearestPlanes(q, params.num_plane_neighbors, params.max_plane_neighbor_dist, nb);
        c = fitPlaneConstraint(nb, params);
      }
      if (c) out.push_back({planes[i], c->normal, c->offset, false, i});
    }
  }
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
      if (auto c = fitLineConstraint(nb, q, params)) out.push_back({edges[i], c->normal, c->offset, true, i});
    }
  }
  if (map.numPlanePoints() > 0) {
    for (std::size_t i = 0; i < planes.size(); i += stride) {
      const Eigen::Vector3d q = T * planes[i];
      map.nearestPlanes(q, params.num_plane_neighbors, params.max_plane_neighbor_dist, nb);
      if (auto c = fitPlaneConstraint(nb, params)) out.push_back({planes[i], c->normal, c->offset, false, i});
    }
  }
}

}  // namespace cosmo::odometry
