#include "cosmo/odometry/local_feature_map.hpp"

#include "cosmo/odometry/voxel_filter.hpp"

namespace cosmo {

void LocalFeatureMap::add(std::vector<Eigen::Vector3d> edges, std::vector<Eigen::Vector3d> planes) {
  scans_.push_back({std::move(edges), std::move(planes)});
  while (scans_.size() > std::max<std::size_t>(1, max_scans_)) scans_.pop_front();
  std::vector<Eigen::Vector3d> all_edges, all_planes;
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
  edge_tree_.build(thinned(std::move(all_edges), edge_voxel_));
  plane_tree_.build(thinned(std::move(all_planes), planar_voxel_));
}

void LocalFeatureMap::clear() {
  scans_.clear();
  edge_tree_.build({});
  plane_tree_.build({});
}

namespace {
void nearestIn(const KdTree3& tree, const Eigen::Vector3d& q, int k, double max_dist, std::vector<Eigen::Vector3d>& out) {
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

}  // namespace cosmo
