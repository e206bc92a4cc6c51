#include "cosmo/registration/global_registration.hpp"

#include <cmath>
#include <optional>

#include "cosmo/registration/consistency_graph.hpp"
#include "cosmo/registration/feature_matching.hpp"
#include "cosmo/registration/graph_pruning.hpp"
#include "cosmo/registration/kdtree.hpp"
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

  // Pairwise-consistency graph and its max k-core.
  std::vector<Eigen::Vector3f> cs(corr.size()), ct(corr.size());
  for (std::size_t i = 0; i < corr.size(); ++i) {
    cs[i] = src.points[static_cast<std::size_t>(src.keypoints[static_cast<std::size_t>(corr[i].source)])];
    ct[i] = tgt.points[static_cast<std::size_t>(tgt.keypoints[static_cast<std::size_t>(corr[i].target)])];
  }
  ConsistencyGraph graph;
  if (corr.size() >= 3) {
    graph = ConsistencyGraph::fromCorrespondences(cs, ct, 2.0 * p.noise_bound);
    // The first maximum-clique search finds the max k-core on the way; otherwise it is computed here.
    if (!p.use_max_clique || p.max_hypotheses < 1) r.max_core_size = maxKCore(graph).size();
  }
  notifyStage(observer, "pruning");

  std::optional<KdTree<3>> target_tree;
  if (!tgt.points.empty()) target_tree.emplace(tgt.points.front().data(), tgt.points.size());
  // Structure points (not ground-like) of the source, for the structure overlap (measured in the same pass as
  // the overlap of all points).
  std::vector<unsigned char> src_structure(src.points.size(), 0);
  for (std::size_t i = 0; i < src.points.size() && i < src.normals.size(); ++i)
    src_structure[i] = std::fabs(src.normals[i].z()) < static_cast<float>(p.structure_max_normal_z);
  // ICP iterates on an evenly strided subset of the source (every k-th point); the overlap uses all points.
  std::vector<Eigen::Vector3f> icp_source;
  const std::size_t stride = p.icp_max_points > 0 ? (src.points.size() + p.icp_max_points - 1) / p.icp_max_points : 1;
  if (stride > 1) {
    icp_source.reserve(src.points.size() / stride + 1);
    for (std::size_t i = 0; i < src.points.size(); i += stride) icp_source.push_back(src.points[i]);
  }
  const std::vector<Eigen::Vector3f>& icp_points = stride > 1 ? icp_source : src.points;

  // Hypotheses: the maximum clique (or k-core) first; while the gate rejects, the maximum clique among the
  // correspondences that no previous solution explains. Solve, refine, measure the overlap, verify.
  std::vector<int> remaining(corr.size());
  for (std::size_t i = 0; i < corr.size(); ++i) remaining[i] = static_cast<int>(i);
  bool solved = false;
  RegistrationResult best;
  const std::size_t min_clique = std::max<std::size_t>(3, p.min_final_inliers);
  for (int h = 0; h < p.max_hypotheses && remaining.size() >= 3; ++h) {
    std::vector<int> pruned;
    bool proven = true;
    {
      const ConsistencyGraph sub = h == 0 ? ConsistencyGraph() : graph.induced(remaining);
      const ConsistencyGraph& g = h == 0 ? graph : sub;
      std::vector<int> local;
      if (p.use_max_clique) {
        CliqueResult clique = maxClique(g, p.max_clique_nodes);
        if (h == 0) r.max_core_size = clique.max_core_size;
        local = std::move(clique.vertices);
        proven = clique.proven_maximum;
      } else {
        local = maxKCore(g);
      }
      for (const int v : local) pruned.push_back(h == 0 ? v : remaining[static_cast<std::size_t>(v)]);
    }
    if (h > 0 && pruned.size() < min_clique) break;
    notifyStage(observer, "pruning");
    RegistrationResult cand = r;
    cand.pruned_inliers = pruned.size();
    cand.clique_proven = proven;
    cand.hypothesis = h;
    if (pruned.size() < 3) {
      if (h == 0) best = cand;
      break;
    }

    // Robust solve on the survivors.
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
    notifyStage(observer, "solve");
    if (!est.ok) {
      if (h == 0) best = cand;
      break;
    }
    cand.T_target_source = est.T;
    cand.final_inliers = est.inliers.size();

    // Local refinement on the downsampled clouds; kept when small, or when it raises the overlap (the overlap
    // before it is only needed for that comparison).
    if (target_tree) {
      auto overlapAt = [&](const Pose3& T) {
        return overlapFractions(src.points, src_structure, *target_tree, T, p.icp_max_distance);
      };
      std::optional<Overlaps> overlap;
      if (p.refine && p.icp_iterations > 0) {
        const IcpResult icp = refinePointToPlane(icp_points, *target_tree, tgt.points, tgt.normals,
                                                 cand.T_target_source, p.icp_max_distance, p.icp_iterations);
        const Pose3 delta = cand.T_target_source.inverse() * icp.T;
        const bool small = delta.translation().norm() <= p.icp_max_correction_m &&
                           rotationAngle(delta) <= p.icp_max_correction_deg * M_PI / 180.0;
        if (icp.matched >= 6 && icp.T.matrix().allFinite()) {
          const Overlaps overlap1 = overlapAt(icp.T);
          const Overlaps overlap0 = small ? Overlaps() : overlapAt(cand.T_target_source);
          if (small || overlap1.all > overlap0.all) {
            cand.T_target_source = icp.T;
            cand.refined = true;
            overlap = overlap1;
          } else {
            overlap = overlap0;
          }
        }
      }
      if (!overlap) overlap = overlapAt(cand.T_target_source);
      cand.overlap = overlap->all;
      cand.structure_overlap = overlap->flagged;
    }
    notifyStage(observer, "refine");
    solved = true;
    cand.hypotheses = h + 1;
    applyGate(p, cand);
    const bool better = h == 0 || cand.valid ||
                        (!best.valid && cand.final_inliers >= p.min_final_inliers &&
                         (best.final_inliers < p.min_final_inliers || cand.overlap > best.overlap));
    if (better) best = cand;
    best.hypotheses = h + 1;
    if (cand.valid) break;
    // Next hypothesis: drop the clique and every correspondence this solution explains.
    std::vector<int> next;
    std::vector<char> in_clique(corr.size(), 0);
    for (const int i : pruned) in_clique[static_cast<std::size_t>(i)] = 1;
    const Eigen::Matrix3f R = cand.T_target_source.linear().cast<float>();
    const Eigen::Vector3f t = cand.T_target_source.translation().cast<float>();
    const float bound = static_cast<float>(2.0 * p.noise_bound);
    for (const int i : remaining) {
      const auto k = static_cast<std::size_t>(i);
      if (!in_clique[k] && (R * cs[k] + t - ct[k]).norm() > bound) next.push_back(i);
    }
    remaining.swap(next);
  }
  if (solved || corr.size() >= 3) {
    const std::size_t correspondences = r.correspondences, core = r.max_core_size;
    r = best;
    r.correspondences = correspondences;
    r.max_core_size = core;
    r.source_points = src.points.size();
    r.target_points = tgt.points.size();
    r.source_keypoints = src.keypoints.size();
    r.target_keypoints = tgt.keypoints.size();
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
