#pragma once
// Parameters of the LOAM odometry (feature extraction, local map, registration, motion model). Defaults are
// the values COSMO-Bench used (evalio's LOAM pipeline, spec section 4 item 1); `fromConfig` reads
// config/odometry.yaml (section `odometry`, or the root when there is no such section).
#include <cstddef>

#include "cosmo/common/config.hpp"

namespace cosmo::odometry {

struct LoamParams {
  // --- scan lines -------------------------------------------------------------------------------------------
  /// Beam count used when the scan has no `ring` field and the beam count cannot be estimated from the data.
  int fallback_scan_lines = 64;
  /// Points closer than this (m) are dropped before feature extraction (the robot body, NaN-like zeros).
  double min_range = 1.0;
  /// Points farther than this (m) are dropped.
  double max_range = 120.0;
  /// A scan with fewer valid points is not registered (the motion model is used; a first scan starts an empty map).
  int min_scan_points = 100;

  // --- feature extraction (spec 4.1) --------------------------------------------------------------------------
  int neighbor_points = 3;               ///< points on each side used for the curvature
  int number_sectors = 6;                ///< sectors per scan line
  int max_edge_feats_per_sector = 5;     ///< edge features kept per sector
  int max_planar_feats_per_sector = 50;  ///< planar features kept per sector
  double edge_feat_threshold = 100.0;    ///< unnormalised curvature (m^2) above which a point is an edge
  double planar_feat_threshold = 1.0;    ///< unnormalised curvature (m^2) below which a point is planar
  double occlusion_thresh = 0.5;         ///< range jump (m) between neighbours marking an occlusion boundary
  double parallel_thresh = 1.0;          ///< range jump (fraction of range) to both neighbours: beam || surface

  // --- local map --------------------------------------------------------------------------------------------
  int num_local_map_scans = 3;  ///< scans whose features form the local map
  /// Voxel thinning (m, 0 = off) of the local map's edge / planar points (newest scan's point kept per voxel)
  /// and of each scan's planar features before registration (LOAM's "less flat" downsampling). Fewer, better
  /// spread points: faster k-NN and tree builds, and plane neighbours that are not copies of one point. The map
  /// thinning is off by default because it hides the featureless-corridor degeneracy flag (test
  /// LoamDegenerate.FeaturelessCorridor...).
  double map_edge_voxel_size = 0.0;
  double map_planar_voxel_size = 0.0;
  /// Coarser values trade accuracy for speed (docs/design.md).
  double planar_feature_voxel_size = 0.2;
  /// A registered scan enters the local map only when the sensor moved at least this far (m) or turned at
  /// least this much (deg) since the newest scan in the map (0 / 0: every scan, the default). A standing
  /// sensor fills the map with copies of one scan whose duplicate neighbours fail the plane fits; keeping them
  /// out helps a standing start but hides the featureless-corridor degeneracy flag, which comes from those
  /// failed fits (test LoamDegenerate.FeaturelessCorridor...), so it is off by default.
  double map_insert_min_translation = 0.0;
  double map_insert_min_rotation_deg = 0.0;

  // --- registration (spec 4.1) ------------------------------------------------------------------------------
  int max_icf_iterations = 20;                ///< iterations of re-association + Gauss-Newton step
  double position_convergence_thresh = 1e-3;  ///< stop when the translation update (m) is below this ...
  double rotation_convergence_thresh = 1e-4;  ///< ... and the rotation update (rad) below this
  int num_edge_neighbors = 5;                 ///< map edge points searched per edge feature
  double max_edge_neighbor_dist = 2.0;        ///< (m) farther edge neighbours are ignored
  int min_line_fit_points = 3;                ///< fewer edge neighbours: no line residual
  double min_line_condition_number = 5.0;     ///< largest / middle eigenvalue of the neighbours' scatter
  int num_plane_neighbors = 5;                ///< map planar points searched per planar feature
  double max_plane_neighbor_dist = 4.0;       ///< (m) farther plane neighbours are ignored
  double max_avg_point_plane_dist = 0.2;      ///< (m) plane fits with a larger mean residual are rejected
  int min_plane_fit_points = 4;               ///< fewer plane neighbours: no plane residual
  int icf_inner_steps = 4;                    ///< Gauss-Newton steps per association (fewer once converged)
  /// Coarse to fine: a subsample of about this many features converges to the thresholds above, then all
  /// features polish it, associating again only while a round moves the pose by more than
  /// fine_convergence_factor times the thresholds.
  int coarse_features = 1000;
  double fine_convergence_factor = 10.0;

  // --- robustness (ours; not in the paper) ---------------------------------------------------------------------
  /// Plane fits need neighbours spread in 2D: middle / largest eigenvalue of their scatter at least this
  /// (rejects neighbours that all lie on one scan line, which pull the estimate towards zero motion).
  double min_plane_spread_ratio = 0.05;
  /// Plane fits whose neighbours are not flat, smallest / middle eigenvalue of their scatter above this, are
  /// rejected (0 = off, the default). Neighbours that straddle two surfaces (a wall's foot, a car's side) fit a
  /// tilted plane, and for a sensor at a constant height those tilts add up to a pitch bias. Off by default
  /// because it also rejects good fits of a swaying sensor and costs translation at 2 cm range noise;
  /// plane_off_surface_min_dist below is the default remedy (docs/design.md).
  double max_plane_planarity = 0.0;
  /// (m) Off-surface neighbour test (0 = off). A plane neighbour set (of at least 5) that is not flat
  /// (smallest / middle scatter eigenvalue above 0.01) and spreads more than this along its normal (square root of
  /// the smallest eigenvalue) is rejected when one neighbour alone makes it so: without that neighbour the
  /// smallest eigenvalue drops at least tenfold (a wall-foot or kerb point among ground points). Unlike
  /// max_plane_planarity it keeps sets that are uneven as a whole (a swaying sensor's scans registered slightly
  /// apart). Figures: docs/benchmarks.md (bench_odometry --only cd).
  double plane_off_surface_min_dist = 0.02;
  /// The off-surface test's other numbers: the fewest neighbours it looks at, the flatness (smallest / middle
  /// eigenvalue) above which it looks for a single cause, and the factor by which dropping that neighbour must
  /// lower the smallest eigenvalue.
  int plane_off_surface_min_neighbors = 5;
  double plane_off_surface_flatness = 0.01;
  double plane_off_surface_drop = 0.1;
  double huber_delta = 0.1;  ///< (m) Huber kernel width on the point-line / point-plane distances
  /// An initial guess whose inlier fraction (features with a correspondence closer than `inlier_dist`) is
  /// below this triggers a coarse yaw search around the best guess.
  double min_guess_inlier_fraction = 0.5;
  /// Guesses are scored on a subsample of about this many features.
  int guess_score_features = 400;
  /// A constant-velocity guess scoring below this is compared with zero motion (the better one is kept).
  double zero_motion_guess_below = 0.9;
  double inlier_dist = 0.3;           ///< (m) residual counted as an inlier when scoring guesses
  double yaw_search_step_deg = 10.0;  ///< yaw step of the coarse search
  double yaw_search_max_deg = 50.0;   ///< yaw range (+-) of the coarse search
  /// The yaw search also runs when the registration turned at least this far from its guess (an unpredicted
  /// turn, where a local registration can settle part-way with a fair inlier fraction); 0: only on poor fits.
  double yaw_search_correction_deg = 5.0;
  /// The yaw search registers its best candidate only when that candidate scores this much above the first
  /// registration's pose, and keeps the result only when its inlier fraction is higher by yaw_search_margin
  /// (yaw_search_margin_after_turn after an unpredicted turn, where the first registration is already suspect).
  double yaw_search_min_gain = 0.05;
  double yaw_search_margin = 0.1;
  double yaw_search_margin_after_turn = 0.02;
  /// Degeneracy: directions of the Gauss-Newton system with an eigenvalue below this times the number of
  /// constraints keep the initial guess (solution remapping) and the result is flagged.
  double min_eigenvalue_per_constraint = 1e-3;
  /// Fewer usable correspondences than this after registration: degenerate, the motion model is used.
  int min_correspondences = 30;
  /// Deskew features with the current motion estimate when the scan carries per-point times.
  bool deskew = true;
  /// The features are deskewed with the predicted (previous) motion; only when the registered motion differs
  /// from it by more than these (m, deg) are they deskewed again with the estimate and re-registered.
  /// A walker's roll / pitch sway is not predicted by the previous scan's motion, hence the small rotation
  /// threshold; 0 (always re-deskew) feeds the estimate back every scan and oscillates: the threshold is a
  /// dead band (docs/design.md).
  double deskew_reestimate_translation = 0.1;
  double deskew_reestimate_rotation_deg = 0.05;
  /// The re-deskewed features are registered by this many robust Gauss-Newton steps (at most) on the first
  /// registration's correspondences (the map did not change, the features moved by centimetres): no k-NN
  /// search, no line / plane fits. 0: a full registration (re-association from the first estimate).
  int deskew_refine_steps = 4;
  /// At most this many re-deskews per scan.
  int deskew_reestimate_passes = 2;
  /// > 0: the refinement above estimates the rotation over the sweep with the pose (refineContinuousRotation: the
  /// sweep's start rotation is a third unknown, tied to the previous scan's rotation with this weight relative to
  /// the scan's rotational information) instead of re-deskewing once with the estimate; 0: the re-deskew. A
  /// stiffer tie oscillates (docs/design.md). Not used with deskew_planar_only, nor in fast turns: a rotation
  /// correction above deskew_rotation_max_correction_deg, or a sweep predicted to turn by more than
  /// deskew_rotation_max_sweep_deg, where the rotation is not linear within the sweep and the re-deskew with the
  /// estimate handles it.
  double deskew_rotation_tie = 0.1;
  double deskew_rotation_max_correction_deg = 2.0;
  double deskew_rotation_max_sweep_deg = 5.0;
  /// Deskew with the x / y / yaw part of the motion only. Off by default: the walking sway (roll / pitch) needs
  /// the full 6-DoF deskew.
  bool deskew_planar_only = false;

  /// Reads the keys above (same names) from `cfg` (its `odometry` child when present).
  static LoamParams fromConfig(const ConfigNode& cfg);

  /// The YAML keys, one per member (common/param_list.hpp).
  template <class Visitor>
  void visit(Visitor&& v) {
    v("fallback_scan_lines", fallback_scan_lines);
    v("min_range", min_range);
    v("max_range", max_range);
    v("min_scan_points", min_scan_points);
    v("neighbor_points", neighbor_points);
    v("number_sectors", number_sectors);
    v("max_edge_feats_per_sector", max_edge_feats_per_sector);
    v("max_planar_feats_per_sector", max_planar_feats_per_sector);
    v("edge_feat_threshold", edge_feat_threshold);
    v("planar_feat_threshold", planar_feat_threshold);
    v("occlusion_thresh", occlusion_thresh);
    v("parallel_thresh", parallel_thresh);
    v("num_local_map_scans", num_local_map_scans);
    v("max_icf_iterations", max_icf_iterations);
    v("position_convergence_thresh", position_convergence_thresh);
    v("rotation_convergence_thresh", rotation_convergence_thresh);
    v("num_edge_neighbors", num_edge_neighbors);
    v("max_edge_neighbor_dist", max_edge_neighbor_dist);
    v("min_line_fit_points", min_line_fit_points);
    v("min_line_condition_number", min_line_condition_number);
    v("num_plane_neighbors", num_plane_neighbors);
    v("max_plane_neighbor_dist", max_plane_neighbor_dist);
    v("max_avg_point_plane_dist", max_avg_point_plane_dist);
    v("min_plane_fit_points", min_plane_fit_points);
    v("icf_inner_steps", icf_inner_steps);
    v("coarse_features", coarse_features);
    v("fine_convergence_factor", fine_convergence_factor);
    v("min_plane_spread_ratio", min_plane_spread_ratio);
    v("max_plane_planarity", max_plane_planarity);
    v("plane_off_surface_min_dist", plane_off_surface_min_dist);
    v("plane_off_surface_min_neighbors", plane_off_surface_min_neighbors);
    v("plane_off_surface_flatness", plane_off_surface_flatness);
    v("plane_off_surface_drop", plane_off_surface_drop);
    v("huber_delta", huber_delta);
    v("min_guess_inlier_fraction", min_guess_inlier_fraction);
    v("guess_score_features", guess_score_features);
    v("zero_motion_guess_below", zero_motion_guess_below);
    v("inlier_dist", inlier_dist);
    v("yaw_search_step_deg", yaw_search_step_deg);
    v("yaw_search_max_deg", yaw_search_max_deg);
    v("yaw_search_correction_deg", yaw_search_correction_deg);
    v("yaw_search_min_gain", yaw_search_min_gain);
    v("yaw_search_margin", yaw_search_margin);
    v("yaw_search_margin_after_turn", yaw_search_margin_after_turn);
    v("min_correspondences", min_correspondences);
    v("min_eigenvalue_per_constraint", min_eigenvalue_per_constraint);
    v("map_edge_voxel_size", map_edge_voxel_size);
    v("map_planar_voxel_size", map_planar_voxel_size);
    v("planar_feature_voxel_size", planar_feature_voxel_size);
    v("map_insert_min_translation", map_insert_min_translation);
    v("map_insert_min_rotation_deg", map_insert_min_rotation_deg);
    v("deskew", deskew);
    v("deskew_planar_only", deskew_planar_only);
    v("deskew_reestimate_translation", deskew_reestimate_translation);
    v("deskew_reestimate_rotation_deg", deskew_reestimate_rotation_deg);
    v("deskew_refine_steps", deskew_refine_steps);
    v("deskew_reestimate_passes", deskew_reestimate_passes);
    v("deskew_rotation_tie", deskew_rotation_tie);
    v("deskew_rotation_max_correction_deg", deskew_rotation_max_correction_deg);
    v("deskew_rotation_max_sweep_deg", deskew_rotation_max_sweep_deg);
  }
};

}  // namespace cosmo::odometry
