#include "cosmo/registration/global_registration.hpp"

#include <cmath>

#include "cosmo/registration/consistency_graph.hpp"
#include "cosmo/registration/feature_matching.hpp"
#include "cosmo/registration/graph_pruning.hpp"
#include "cosmo/registration/icp_refinement.hpp"
#include "cosmo/registration/registration_gate.hpp"
#include "cosmo/registration/robust_solver.hpp"

namespace cosmo {

GlobalRegistration::GlobalRegistration(const RegistrationParams& p) : params_(p) {}

RegistrationResult GlobalRegistration::align(const Scan& source, const Scan& target) const {
  return align(source, target, nullptr);
}

RegistrationResult GlobalRegistration::align(const Scan& source, const Scan& target, StageObserver* observer) const {
  const FeatureCloud src = prepare(source, observer);
  const FeatureCloud tgt = prepare(target, observer);
  return align(src, tgt, observer);
}

FeatureCloud GlobalRegistration::prepare(const Scan& scan, StageObserver* observer) const {
  return computeFeatureCloud(scan, params_, observer);
}

RegistrationResult GlobalRegistration::align(const FeatureCloud& src, const FeatureCloud& tgt,
                                             StageObserver* observer) const {
  const RegistrationParams& p = params_;
  RegistrationResult r;
  r.source_points = src.points.size();
  r.target_points = tgt.points.size();
  r.source_keypoints = src.keypoints.size();
  r.target_keypoints = tgt.keypoints.size();

  // Correspondences in feature space.
  const std::vector<Correspondence> corr = matchFeatures(src.features, tgt.features, p.max_correspondences,
                                                         p.mutual_filter, static_cast<float>(p.matching_eps));
  r.correspondences = corr.size();
  notifyStage(observer, "matching");

  // Pairwise-consistency graph, max k-core, max clique.
  std::vector<Eigen::Vector3f> cs(corr.size()), ct(corr.size());
  for (std::size_t i = 0; i < corr.size(); ++i) {
    cs[i] = src.points[static_cast<std::size_t>(src.keypoints[static_cast<std::size_t>(corr[i].source)])];
    ct[i] = tgt.points[static_cast<std::size_t>(tgt.keypoints[static_cast<std::size_t>(corr[i].target)])];
  }
  std::vector<int> pruned;
  if (corr.size() >= 3) {
    const ConsistencyGraph graph = ConsistencyGraph::fromCorrespondences(cs, ct, 2.0 * p.noise_bound);
    const std::vector<int> core = maxKCore(graph);
    r.max_core_size = core.size();
    if (p.use_max_clique) {
      const CliqueResult clique = maxClique(graph, p.max_clique_nodes);
      pruned = clique.vertices;
      r.clique_proven = clique.proven_maximum;
    } else {
      pruned = core;
    }
  }
  r.pruned_inliers = pruned.size();
  notifyStage(observer, "pruning");

  // Robust solve on the survivors.
  bool solved = false;
  if (pruned.size() >= 3) {
    std::vector<Eigen::Vector3d> ps, pt;
    ps.reserve(pruned.size()), pt.reserve(pruned.size());
    for (const int i : pruned) {
      ps.push_back(cs[static_cast<std::size_t>(i)].cast<double>());
      pt.push_back(ct[static_cast<std::size_t>(i)].cast<double>());
    }
    GncParams gnc;
    gnc.noise_bound = p.noise_bound;
    gnc.factor = p.gnc_factor;
    gnc.max_iterations = p.gnc_max_iterations;
    gnc.cost_tolerance = p.gnc_cost_tolerance;
    const RigidEstimate est = solveRobustRigid(ps, pt, gnc, p.max_rotation_pairs);
    if (est.ok) {
      r.T_target_source = est.T;
      r.final_inliers = est.inliers.size();
      solved = true;
    }
  }
  notifyStage(observer, "solve");

  // Local refinement on the downsampled clouds.
  if (solved && p.refine && p.icp_iterations > 0) {
    const IcpResult icp = refinePointToPlane(src.points, tgt.points, tgt.normals, r.T_target_source,
                                             p.icp_max_distance, p.icp_iterations);
    const Pose3 delta = r.T_target_source.inverse() * icp.T;
    const bool small = delta.translation().norm() <= p.icp_max_correction_m &&
                       rotationAngle(delta) <= p.icp_max_correction_deg * M_PI / 180.0;
    if (small && icp.matched >= 6) {
      r.T_target_source = icp.T;
      r.refined = true;
    }
    r.overlap = src.points.empty() ? 0.0 : static_cast<double>(icp.matched) / static_cast<double>(src.points.size());
  } else if (solved && p.min_overlap > 0.0) {
    // Overlap at the global solution (one ICP iteration counts the matches; its update is not used).
    const IcpResult probe = refinePointToPlane(src.points, tgt.points, tgt.normals, r.T_target_source,
                                               p.icp_max_distance, 1);
    r.overlap = src.points.empty() ? 0.0 : static_cast<double>(probe.matched) / static_cast<double>(src.points.size());
  }
  notifyStage(observer, "refine");

  if (!solved && r.correspondences >= p.min_correspondences) {
    r.reason = "pruning left fewer than 3 consistent correspondences";
    r.valid = false;
  } else {
    applyGate(p, r);
  }
  notifyStage(observer, "gate");
  return r;
}

}  // namespace cosmo
