#pragma once
// Parameters of the global (correspondence-based) registration of loop closures, KISS-Matcher style.
// Defaults follow KISS-Matcher's gains for a 0.3 m voxel; every value is read from config/registration.yaml.
#include <cstddef>
#include <cstdint>
#include <string>

#include "cosmo/common/config.hpp"

namespace cosmo::registration {

struct RegistrationParams {
  // --- preprocessing -------------------------------------------------------------------------------------
  double voxel_size = 0.3;  ///< voxel edge (m) of the downsampling (one centroid per voxel)
  double min_range = 0.5;   ///< points closer than this to the sensor are dropped (m); 0 = keep
  double max_range = 0.0;   ///< points farther than this are dropped (m); 0 = keep all
  // --- features ------------------------------------------------------------------------------------------
  double normal_radius = 0.9;            ///< radius (m) of the normal estimation (3 x voxel)
  double fpfh_radius = 1.5;              ///< radius (m) of the FPFH neighbourhood (5 x voxel)
  double spfh_radius = 0.0;              ///< radius (m) of each point's SPFH (fast backend; 0 = fpfh_radius as PCL)
  std::size_t min_normal_neighbors = 5;  ///< points with fewer neighbours get no normal and no feature
  double max_linearity = 0.99;           ///< drop points whose neighbourhood is this linear, (l1-l2)/l1 (fast backend)
  double keypoint_voxel = 0.9;           ///< FPFH only for one point per voxel of this size (fast backend; 0 = all)
  bool fast_features = true;  ///< own single-search normals+FPFH (true) or PCL NormalEstimation+FPFHEstimation
  // --- correspondences -----------------------------------------------------------------------------------
  std::size_t max_correspondences = 5000;  ///< cap on mutual-NN correspondences (best feature distance first)
  bool mutual_filter = true;               ///< keep only mutual nearest neighbours in feature space
  double matching_eps = 10.0;              ///< (1+eps)-approximate kd-tree search in FPFH space; 0 = exact
  // --- pruning -------------------------------------------------------------------------------------------
  double noise_bound = 0.3;               ///< max residual (m) of an inlier correspondence; edges tolerate 2x this
  bool use_max_clique = true;             ///< max clique inside the max k-core (else the max k-core itself)
  std::uint64_t max_clique_nodes = 1000;  ///< branch-and-bound node budget (deterministic cut-off)
  int max_hypotheses = 3;                 ///< cliques tried in turn while the gate rejects (each next one found after
                                          ///< removing the correspondences the previous solutions explain); 1 = off
  // --- robust solve --------------------------------------------------------------------------------------
  double gnc_factor = 1.4;                ///< GNC-TLS: growth factor of the control parameter mu
  int gnc_max_iterations = 100;           ///< GNC-TLS: iteration cap
  double gnc_cost_tolerance = 1e-6;       ///< GNC-TLS: stop when the cost changes less than this
  std::size_t max_rotation_pairs = 5000;  ///< cap on translation-invariant pairs used for the rotation
  // --- refinement ----------------------------------------------------------------------------------------
  bool refine = true;                   ///< point-to-plane ICP on the downsampled full clouds after the global solve
  int icp_iterations = 20;              ///< ICP iteration cap
  double icp_max_distance = 0.9;        ///< ICP correspondence distance (m)
  std::size_t icp_max_points = 2500;    ///< ICP iterates on every k-th source point, k = ceil(n / this); 0 = all
  double icp_max_correction_m = 1.0;    ///< a refinement that moves farther than this is discarded (m) ...
  double icp_max_correction_deg = 5.0;  ///< ... or rotates more than this (deg), unless it raises the overlap
  // --- validity gate (never looks at ground truth) -------------------------------------------------------
  std::size_t min_final_inliers = 3;     ///< accept only with at least this many consistent inliers
  std::size_t min_correspondences = 10;  ///< below this the problem is declared degenerate
  double min_inlier_ratio = 0.0;         ///< final inliers / correspondences must reach this (0 = off)
  double min_overlap = 0.5;             ///< fraction of source points within icp_max_distance after the solve (0 = off)
  double min_structure_overlap = 0.62;  ///< the same over the source's structure points only (0 = off)
  double structure_max_normal_z = 0.9;  ///< structure point: |normal z| below this (not ground / ceiling-like)
  /// Gate preset (`gate:` key). "strict": every test above. "paper": what KISS-Matcher itself checks (enough
  /// correspondences, enough consistent final inliers), without the two overlap tests (min_overlap and
  /// min_structure_overlap set to 0), which lets through the spurious registrations the paper describes.
  std::string gate = "strict";

  static RegistrationParams fromConfig(const ConfigNode& node);

  /// The YAML keys, one per member (common/param_list.hpp).
  template <class Visitor>
  void visit(Visitor&& v) {
    v("voxel_size", voxel_size);
    v("min_range", min_range);
    v("max_range", max_range);
    v("normal_radius", normal_radius);
    v("fpfh_radius", fpfh_radius);
    v("spfh_radius", spfh_radius);
    v("min_normal_neighbors", min_normal_neighbors);
    v("max_linearity", max_linearity);
    v("fast_features", fast_features);
    v("keypoint_voxel", keypoint_voxel);
    v("max_correspondences", max_correspondences);
    v("mutual_filter", mutual_filter);
    v("matching_eps", matching_eps);
    v("noise_bound", noise_bound);
    v("use_max_clique", use_max_clique);
    v("max_clique_nodes", max_clique_nodes);
    v("max_hypotheses", max_hypotheses);
    v("gnc_factor", gnc_factor);
    v("gnc_max_iterations", gnc_max_iterations);
    v("gnc_cost_tolerance", gnc_cost_tolerance);
    v("max_rotation_pairs", max_rotation_pairs);
    v("refine", refine);
    v("icp_iterations", icp_iterations);
    v("icp_max_distance", icp_max_distance);
    v("icp_max_points", icp_max_points);
    v("icp_max_correction_m", icp_max_correction_m);
    v("icp_max_correction_deg", icp_max_correction_deg);
    v("min_final_inliers", min_final_inliers);
    v("min_correspondences", min_correspondences);
    v("min_inlier_ratio", min_inlier_ratio);
    v("min_overlap", min_overlap);
    v("min_structure_overlap", min_structure_overlap);
    v("structure_max_normal_z", structure_max_normal_z);
    v("gate", gate);
  }
};

}  // namespace cosmo::registration
