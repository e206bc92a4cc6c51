#include "cosmo/odometry/local_feature_map.hpp"

namespace cosmo {

void LocalFeatureMap::add(std::vector<Eigen::Vector3d> edges, std::vector<Eigen::Vector3d> planes) {
  scans_.push_back({std::move(edges), std::move(planes)});
  while (scans_.size() > std::max<std::size_t>(1, max_scans_)) scans_.pop_front();
  std::vector<Eigen::Vector3d> all_edges, all_planes;
  for (const auto& s : scans_) {
    all_edges.insert(all_edges.end(), s.edges.begin(), s.edges.end());
    all_planes.insert(all_planes.end(), s.planes.begin(), s.planes.end());
  }
  edge_tree_.build(all_edges);
  plane_tree_.build(all_planes);
}

void LocalFeatureMap::clear() {
  scans_.clear();
  edge_tree_.build({});
  plane_tree_.build({});
}

}  // namespace cosmo
