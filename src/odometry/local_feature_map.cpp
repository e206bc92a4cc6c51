#include "cosmo/odometry/local_feature_map.hpp"

#include "cosmo/common/voxel_grid.hpp"

namespace cosmo::odometry {

void LocalFeatureMap::add(std::vector<Eigen::Vector3d> edges, std::vector<Eigen::Vector3d> planes) {
  // The union is newest scan first. Without thinning, a tree is built with its points in the previous tree's
  // order (the older scans', shifted behind the new scan; the dropped oldest scan is last in the old union)
  // followed by the new scan: the same tree as from the plain order, built faster (fewer mispredicted partition
  // branches; docs/benchmarks.md, LOAM odometry).
  std::size_t old_edges = 0, old_planes = 0, dropped_edges = 0, dropped_planes = 0;
  for (const Entry& s : scans_) old_edges += s.edges.size(), old_planes += s.planes.size();
  const std::size_t new_edges = edges.size(), new_planes = planes.size();
  scans_.push_back({std::move(edges), std::move(planes)});
  while (scans_.size() > std::max<std::size_t>(1, max_scans_)) {
    dropped_edges += scans_.front().edges.size();
    dropped_planes += scans_.front().planes.size();
    scans_.pop_front();
  }
  std::vector<Eigen::Vector3d> all_edges, all_planes;
  all_edges.reserve(old_edges + new_edges - dropped_edges);
  all_planes.reserve(old_planes + new_planes - dropped_planes);
  for (auto s = scans_.rbegin(); s != scans_.rend(); ++s) {  // newest first: its points win the voxels
    all_edges.insert(all_edges.end(), s->edges.begin(), s->edges.end());
    all_planes.insert(all_planes.end(), s->planes.begin(), s->planes.end());
  }
  auto thinned = [](std::vector<Eigen::Vector3d> pts, double voxel) {
    if (!(voxel > 0.0)) return pts;
    std::vector<Eigen::Vector3d> out;
    const auto keep = voxelFilterIndices(pts, voxel);
    out.reserve(keep.size());
    for (std::uint32_t i : keep) out.push_back(pts[i]);
    return out;
  };
  auto rebuild = [this](KdTree3& tree, std::vector<Eigen::Vector3d> pts, double voxel, std::size_t old_total,
                        std::size_t dropped, std::size_t added) {
    if (voxel > 0.0) {  // thinning renumbers the points: plain order
      tree.build(std::move(pts));
      return;
    }
    tree.treeOrder(order_);
    const std::size_t kept_old = old_total - dropped;
    std::size_t n = 0;
    for (std::uint32_t i : order_)
      if (i < kept_old) order_[n++] = static_cast<std::uint32_t>(i + added);
    order_.resize(n);
    for (std::size_t i = 0; i < added; ++i) order_.push_back(static_cast<std::uint32_t>(i));
    tree.build(std::move(pts), order_);
  };
  rebuild(edge_tree_, thinned(std::move(all_edges), edge_voxel_), edge_voxel_, old_edges, dropped_edges, new_edges);
  rebuild(plane_tree_, thinned(std::move(all_planes), planar_voxel_), planar_voxel_, old_planes, dropped_planes,
          new_planes);
}

void LocalFeatureMap::clear() {
  scans_.clear();
  edge_tree_.build({});
  plane_tree_.build({});
}

namespace {
void nearestIn(const KdTree3& tree, const Eigen::Vector3d& q, int k, double max_dist,
               std::vector<Eigen::Vector3d>& out) {
  out.clear();
  KnnResult result;
  result.reset(k, max_dist);
  tree.search(q, result);
  for (int i = 0; i < result.size(); ++i) out.push_back(tree.point(result.index(i)));
}
}  // namespace

void LocalFeatureMap::nearestEdges(const Eigen::Vector3d& q, int k, double max_dist,
                                   std::vector<Eigen::Vector3d>& out) const {
  nearestIn(edge_tree_, q, k, max_dist, out);
}

void LocalFeatureMap::nearestPlanes(const Eigen::Vector3d& q, int k, double max_dist,
                                    std::vector<Eigen::Vector3d>& out) const {
  nearestIn(plane_tree_, q, k, max_dist, out);
}

}  // namespace cosmo::odometry
