#include "cosmo/registration/registration_params.hpp"

#include <stdexcept>

namespace cosmo {

namespace {
void require(bool ok, const ConfigNode& node, const std::string& key, const std::string& what) {
  if (!ok) throw std::runtime_error(node.where + (node.where.empty() ? "" : ".") + key + ": " + what);
}
}  // namespace

RegistrationParams RegistrationParams::fromConfig(const ConfigNode& root) {
  // Accept either the whole file (with a `registration:` section) or the section itself.
  const ConfigNode node = root.has("registration") ? root["registration"] : root;
  RegistrationParams p;
  node.read("voxel_size", p.voxel_size);
  node.read("min_range", p.min_range);
  node.read("max_range", p.max_range);
  node.read("normal_radius", p.normal_radius);
  node.read("fpfh_radius", p.fpfh_radius);
  node.read("spfh_radius", p.spfh_radius);
  node.read("min_normal_neighbors", p.min_normal_neighbors);
  node.read("max_linearity", p.max_linearity);
  node.read("fast_features", p.fast_features);
  node.read("keypoint_voxel", p.keypoint_voxel);
  node.read("max_correspondences", p.max_correspondences);
  node.read("mutual_filter", p.mutual_filter);
  node.read("matching_eps", p.matching_eps);
  node.read("noise_bound", p.noise_bound);
  node.read("use_max_clique", p.use_max_clique);
  node.read("max_clique_nodes", p.max_clique_nodes);
  node.read("max_hypotheses", p.max_hypotheses);
  node.read("gnc_factor", p.gnc_factor);
  node.read("gnc_max_iterations", p.gnc_max_iterations);
  node.read("gnc_cost_tolerance", p.gnc_cost_tolerance);
  node.read("max_rotation_pairs", p.max_rotation_pairs);
  node.read("refine", p.refine);
  node.read("icp_iterations", p.icp_iterations);
  node.read("icp_max_distance", p.icp_max_distance);
  node.read("icp_max_points", p.icp_max_points);
  node.read("icp_max_correction_m", p.icp_max_correction_m);
  node.read("icp_max_correction_deg", p.icp_max_correction_deg);
  node.read("min_final_inliers", p.min_final_inliers);
  node.read("min_correspondences", p.min_correspondences);
  node.read("min_inlier_ratio", p.min_inlier_ratio);
  node.read("min_overlap", p.min_overlap);
  node.read("min_structure_overlap", p.min_structure_overlap);
  node.read("structure_max_normal_z", p.structure_max_normal_z);
  node.read("gate", p.gate);
  require(p.gate == "strict" || p.gate == "paper", node, "gate", "expected strict or paper, got '" + p.gate + "'");
  if (p.gate == "paper") {
    p.min_overlap = 0.0;
    p.min_structure_overlap = 0.0;
  }
  require(p.voxel_size > 0.0, node, "voxel_size", "must be > 0");
  require(p.normal_radius > 0.0, node, "normal_radius", "must be > 0");
  require(p.fpfh_radius > 0.0, node, "fpfh_radius", "must be > 0");
  require(p.noise_bound > 0.0, node, "noise_bound", "must be > 0");
  require(p.max_hypotheses >= 1, node, "max_hypotheses", "must be >= 1");
  require(p.gnc_factor > 1.0, node, "gnc_factor", "must be > 1");
  require(p.max_correspondences > 0, node, "max_correspondences", "must be > 0");
  require(p.max_correspondences <= 20000, node, "max_correspondences", "must be <= 20000 (n^2 graph)");
  return p;
}

}  // namespace cosmo
