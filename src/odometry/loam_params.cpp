#include "cosmo/odometry/loam_params.hpp"

namespace cosmo {

LoamParams LoamParams::fromConfig(const ConfigNode& root) {
  const ConfigNode c = root.has("odometry") ? root["odometry"] : root;
  LoamParams p;
  c.read("fallback_scan_lines", p.fallback_scan_lines);
  c.read("min_range", p.min_range);
  c.read("max_range", p.max_range);
  c.read("neighbor_points", p.neighbor_points);
  c.read("number_sectors", p.number_sectors);
  c.read("max_edge_feats_per_sector", p.max_edge_feats_per_sector);
  c.read("max_planar_feats_per_sector", p.max_planar_feats_per_sector);
  c.read("edge_feat_threshold", p.edge_feat_threshold);
  c.read("planar_feat_threshold", p.planar_feat_threshold);
  c.read("occlusion_thresh", p.occlusion_thresh);
  c.read("parallel_thresh", p.parallel_thresh);
  c.read("num_local_map_scans", p.num_local_map_scans);
  c.read("max_icf_iterations", p.max_icf_iterations);
  c.read("position_convergence_thresh", p.position_convergence_thresh);
  c.read("rotation_convergence_thresh", p.rotation_convergence_thresh);
  c.read("num_edge_neighbors", p.num_edge_neighbors);
  c.read("max_edge_neighbor_dist", p.max_edge_neighbor_dist);
  c.read("min_line_fit_points", p.min_line_fit_points);
  c.read("min_line_condition_number", p.min_line_condition_number);
  c.read("num_plane_neighbors", p.num_plane_neighbors);
  c.read("max_plane_neighbor_dist", p.max_plane_neighbor_dist);
  c.read("max_avg_point_plane_dist", p.max_avg_point_plane_dist);
  c.read("min_plane_fit_points", p.min_plane_fit_points);
  c.read("min_plane_spread_ratio", p.min_plane_spread_ratio);
  c.read("max_plane_planarity", p.max_plane_planarity);
  c.read("plane_off_surface_min_dist", p.plane_off_surface_min_dist);
  c.read("huber_delta", p.huber_delta);
  c.read("min_guess_inlier_fraction", p.min_guess_inlier_fraction);
  c.read("inlier_dist", p.inlier_dist);
  c.read("yaw_search_step_deg", p.yaw_search_step_deg);
  c.read("yaw_search_max_deg", p.yaw_search_max_deg);
  c.read("yaw_search_correction_deg", p.yaw_search_correction_deg);
  c.read("min_correspondences", p.min_correspondences);
  c.read("min_eigenvalue_per_constraint", p.min_eigenvalue_per_constraint);
  c.read("map_edge_voxel_size", p.map_edge_voxel_size);
  c.read("map_planar_voxel_size", p.map_planar_voxel_size);
  c.read("planar_feature_voxel_size", p.planar_feature_voxel_size);
  c.read("map_insert_min_translation", p.map_insert_min_translation);
  c.read("map_insert_min_rotation_deg", p.map_insert_min_rotation_deg);
  c.read("deskew", p.deskew);
  c.read("deskew_planar_only", p.deskew_planar_only);
  c.read("deskew_reestimate_translation", p.deskew_reestimate_translation);
  c.read("deskew_reestimate_rotation_deg", p.deskew_reestimate_rotation_deg);
  c.read("deskew_refine_steps", p.deskew_refine_steps);
  c.read("deskew_rotation_tie", p.deskew_rotation_tie);
  return p;
}

}  // namespace cosmo
