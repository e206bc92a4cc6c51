#include "cosmo/registration/global_registration.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "cosmo/registration/consistency_graph.hpp"
#include "cosmo/registration/feature_matching.hpp"
#include "cosmo/registration/graph_pruning.hpp"
#include "cosmo/common/kd_tree.hpp"
#include "cosmo/registration/icp_refinement.hpp"
#include "cosmo/registration/registration_gate.hpp"
#include "cosmo/registration/robust_solver.hpp"

namespace cosmo::registration {

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

namespace {

/// Feature matches and their keypoints' positions (cs[i] in the source, ct[i] in the target).
struct Matches {
  std::vector<Correspondence> corr;
  std::vector<Eigen::Vector3f> cs, ct;
};

Matches matchKeypoints(const FeatureCloud& src, const FeatureCloud& tgt, const RegistrationParams& p) {
  Matches m;
  m.corr = matchFeatures(src.features, tgt.features, p.max_correspondences, p.mutual_filter,
                         static_cast<float>(p.matching_eps));
  m.cs.resize(m.corr.size());
  m.ct.resize(m.corr.size());
  for (std::size_t i = 0; i < m.corr.size(); ++i) {
    m.cs[i] = src.points[static_cast<std::size_t>(src.keypoints[static_cast<std::size_t>(m.corr[i].source)])];
    m.ct[i] = tgt.points[static_cast<std::size_t>(tgt.keypoints[static_cast<std::size_t>(m.corr[i].target)])];
  }
  return m;
}

/// The pairwise-consistency graph; its max k-core's size goes to r when no maximum-clique search finds it on the
/// way.
ConsistencyGraph consistencyGraph(const Matches& m, const RegistrationParams& p, RegistrationResult& r) {
  ConsistencyGraph graph;
  if (m.corr.size() < 3) return graph;
  graph = ConsistencyGraph::fromCorrespondences(m.cs, m.ct, 2.0 * p.noise_bound);
  if (!p.use_max_clique || p.max_hypotheses < 1) r.max_core_size = maxKCore(graph).size();
  return graph;
}

/// What the refinement and the overlap need, built once per pair: the target's k-d tree, the source's structure
/// points (not ground-like, for the structure overlap, measured in the same pass as the overlap of all points)
/// and the evenly strided subset of the source ICP iterates on (every k-th point; the overlap uses all points).
struct RefinementInput {
  std::optional<KdTree<3>> target_tree;
  std::vector<unsigned char> src_structure;
  std::vector<Eigen::Vector3f> icp_source;  ///< empty: ICP on every source point
};

RefinementInput refinementInput(const FeatureCloud& src, const FeatureCloud& tgt, const RegistrationParams& p) {
  RefinementInput in;
  if (!tgt.points.empty()) in.target_tree.emplace(tgt.points.front().data(), tgt.points.size());
  in.src_structure.assign(src.points.size(), 0);
  for (std::size_t i = 0; i < src.points.size() && i < src.normals.size(); ++i)
    in.src_structure[i] = std::fabs(src.normals[i].z()) < static_cast<float>(p.structure_max_normal_z);
  const std::size_t stride = p.icp_max_points > 0 ? (src.points.size() + p.icp_max_points - 1) / p.icp_max_points : 1;
  if (stride > 1) {
    in.icp_source.reserve(src.points.size() / stride + 1);
    for (std::size_t i = 0; i < src.points.size(); i += stride) in.icp_source.push_back(src.points[i]);
  }
  return in;
}

/// Hypothesis h's inliers (indices into the matches): the maximum clique (or k-core) of the graph (h = 0) or of
/// its sub-graph on `remaining`. The first search's max k-core size goes to r.
std::vector<int> hypothesisInliers(const ConsistencyGraph& graph, const std::vector<int>& remaining, int h,
                                   const RegistrationParams& p, RegistrationResult& r, bool& proven) {
  proven = true;
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
  std::vector<int> pruned;
  for (const int v : local) pruned.push_back(h == 0 ? v : remaining[static_cast<std::size_t>(v)]);
  return pruned;
}

/// The robust rigid solve on the inliers.
RigidEstimate solveInliers(const Matches& m, const std::vector<int>& pruned, const RegistrationParams& p) {
  std::vector<Eigen::Vector3d> ps, pt;
  ps.reserve(pruned.size()), pt.reserve(pruned.size());
  for (const int i : pruned) {
    ps.push_back(m.cs[static_cast<std::size_t>(i)].cast<double>());
    pt.push_back(m.ct[static_cast<std::size_t>(i)].cast<double>());
  }
  GncParams gnc;
  gnc.noise_bound = p.noise_bound;
  gnc.factor = p.gnc_factor;
  gnc.max_iterations = p.gnc_max_iterations;
  gnc.cost_tolerance = p.gnc_cost_tolerance;
  return solveRobustRigid(ps, pt, gnc, p.max_rotation_pairs);
}

/// Local refinement on the downsampled clouds, kept when small or when it raises the overlap (the overlap before
/// it is only needed for that comparison); then the candidate's overlaps at its pose.
void refineAndMeasure(const FeatureCloud& src, const FeatureCloud& tgt, const RefinementInput& in,
                      const RegistrationParams& p, RegistrationResult& cand) {
  if (!in.target_tree) return;
  const auto overlapAt = [&](const Pose3& T) {
    return overlapFractions(src.points, in.src_structure, *in.target_tree, T, p.icp_max_distance);
  };
  std::optional<Overlaps> overlap;
  if (p.refine && p.icp_iterations > 0) {
    const std::vector<Eigen::Vector3f>& icp_points = in.icp_source.empty() ? src.points : in.icp_source;
    const IcpResult icp = refinePointToPlane(icp_points, *in.target_tree, tgt.points, tgt.normals, cand.T_target_source,
                                             p.icp_max_distance, p.icp_iterations);
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

/// Whether hypothesis h's gated candidate replaces the best so far: the first always, a valid one, or, while
/// none is valid, one with enough inliers and more overlap.
bool replacesBest(const RegistrationResult& cand, const RegistrationResult& best, int h, const RegistrationParams& p) {
  return h == 0 || cand.valid ||
         (!best.valid && cand.final_inliers >= p.min_final_inliers &&
          (best.final_inliers < p.min_final_inliers || cand.overlap > best.overlap));
}

/// The next hypothesis's matches: `remaining` without the clique and every match the solution explains.
std::vector<int> unexplainedMatches(const Matches& m, const std::vector<int>& remaining, const std::vector<int>& pruned,
                                    const Pose3& T, double noise_bound) {
  std::vector<int> next;
  std::vector<char> in_clique(m.corr.size(), 0);
  for (const int i : pruned) in_clique[static_cast<std::size_t>(i)] = 1;
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  const float bound = static_cast<float>(2.0 * noise_bound);
  for (const int i : remaining) {
    const auto k = static_cast<std::size_t>(i);
    if (!in_clique[k] && (R * m.cs[k] + t - m.ct[k]).norm() > bound) next.push_back(i);
  }
  return next;
}

/// Hypotheses: the maximum clique (or k-core) first; while the gate rejects, the maximum clique among the
/// correspondences that no previous solution explains. Each is solved, refined, measured and gated; returns the
/// best (`solved`: one was solved). `r`: the pair's counts so far (the first search adds its max k-core size).
RegistrationResult bestHypothesis(const FeatureCloud& src, const FeatureCloud& tgt, const Matches& m,
                                  const ConsistencyGraph& graph, const RefinementInput& refinement,
                                  const RegistrationParams& p, StageObserver* observer, RegistrationResult& r,
                                  bool& solved) {
  std::vector<int> remaining(m.corr.size());
  for (std::size_t i = 0; i < m.corr.size(); ++i) remaining[i] = static_cast<int>(i);
  RegistrationResult best;
  const std::size_t min_clique = std::max<std::size_t>(3, p.min_final_inliers);
  for (int h = 0; h < p.max_hypotheses && remaining.size() >= 3; ++h) {
    bool proven = true;
    const std::vector<int> pruned = hypothesisInliers(graph, remaining, h, p, r, proven);
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
    const RigidEstimate est = solveInliers(m, pruned, p);
    notifyStage(observer, "solve");
    if (!est.ok) {
      if (h == 0) best = cand;
      break;
    }
    cand.T_target_source = est.T;
    cand.final_inliers = est.inliers.size();
    refineAndMeasure(src, tgt, refinement, p, cand);
    notifyStage(observer, "refine");
    solved = true;
    cand.hypotheses = h + 1;
    applyGate(p, cand);
    if (replacesBest(cand, best, h, p)) best = cand;
    best.hypotheses = h + 1;
    if (cand.valid) break;
    remaining = unexplainedMatches(m, remaining, pruned, cand.T_target_source, p.noise_bound);
  }
  return best;
}

}  // namespace

RegistrationResult GlobalRegistration::align(const FeatureCloud& src, const FeatureCloud& tgt,
                                             StageObserver* observer) const {
  const RegistrationParams& p = params_;
  RegistrationResult r;
  r.source_points = src.points.size();
  r.target_points = tgt.points.size();
  r.source_keypoints = src.keypoints.size();
  r.target_keypoints = tgt.keypoints.size();

  const Matches matches = matchKeypoints(src, tgt, p);
  r.correspondences = matches.corr.size();
  notifyStage(observer, "matching");
  // The first maximum-clique search finds the max k-core on the way; otherwise consistencyGraph computes it.
  const ConsistencyGraph graph = consistencyGraph(matches, p, r);
  notifyStage(observer, "pruning");
  const RefinementInput refinement = refinementInput(src, tgt, p);

  bool solved = false;
  const RegistrationResult best = bestHypothesis(src, tgt, matches, graph, refinement, p, observer, r, solved);
  if (solved || matches.corr.size() >= 3) {
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

}  // namespace cosmo::registration
