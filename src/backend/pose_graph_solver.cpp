#include "cosmo/backend/pose_graph_solver.hpp"

#include <map>
#include <stdexcept>

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "cosmo/backend/pose_residual.hpp"

namespace cosmo::backend {

const char* selectionName(FactorSelection selection) {
  switch (selection) {
    case FactorSelection::All: return "all";
    case FactorSelection::AllRobust: return "robust";
    case FactorSelection::Inliers: return "inliers";
  }
  return "?";
}

namespace {

/// A pose as one PoseManifold parameter block: quaternion [x, y, z, w], translation.
struct PoseBlock {
  double x[7];
  Pose3 pose() const { return makePose(Eigen::Vector3d(x[4], x[5], x[6]), Eigen::Quaterniond(x[3], x[0], x[1], x[2])); }
};

bool selected(const jrl::PoseFactor& f, FactorSelection selection) {
  return selection != FactorSelection::Inliers || !f.outlier;
}

void checkCovariance(const jrl::PoseFactor& f) {
  if (Eigen::LLT<Matrix6>(f.covariance).info() != Eigen::Success)
    throw std::runtime_error("measurements." + std::string(1, f.robot) + "[" + std::to_string(f.id.entry) +
                             "].measurements[" + std::to_string(f.id.measurement) +
                             "]: covariance is not positive definite");
}

double* blockOf(std::map<jrl::Key, PoseBlock>& blocks, const jrl::PoseGraph& graph, jrl::Key key,
                ceres::Problem& problem, ceres::Manifold* manifold) {
  auto it = blocks.find(key);
  if (it != blocks.end()) return it->second.x;
  const auto init = graph.initialization.find(key);
  if (init == graph.initialization.end()) throw std::runtime_error("no initialization of pose " + jrl::keyName(key));
  PoseBlock& b = blocks[key];
  Eigen::Map<Eigen::Quaterniond>(b.x) = Eigen::Quaterniond(init->second.linear()).normalized();
  Eigen::Map<Eigen::Vector3d>(b.x + 4) = init->second.translation();
  problem.AddParameterBlock(b.x, 7, manifold);
  return b.x;
}

void addFactors(const jrl::PoseGraph& graph, const SolverOptions& options, ceres::Problem& problem,
                std::map<jrl::Key, PoseBlock>& blocks, SolveResult& result) {
  auto* manifold = new PoseManifold;  // owned by the problem
  for (const jrl::PoseFactor& f : graph.factors) {
    if (!selected(f, options.selection)) continue;
    checkCovariance(f);
    double* x1 = blockOf(blocks, graph, f.key1, problem, manifold);
    if (f.kind == jrl::FactorKind::Prior) {
      problem.AddResidualBlock(PriorResidual::create(f.measured, f.covariance), nullptr, x1);
    } else {
      double* x2 = blockOf(blocks, graph, f.key2, problem, manifold);
      ceres::LossFunction* loss = options.selection == FactorSelection::AllRobust && f.isLoopClosure()
                                      ? new ceres::CauchyLoss(options.cauchy_scale)
                                      : nullptr;
      problem.AddResidualBlock(BetweenResidual::create(f.measured, f.covariance), loss, x1, x2);
    }
    ++result.factors_used;
  }
}

/// Levenberg-Marquardt as GTSAM runs it by default: damping λ·I on the tangent space (no Jacobi scaling, LM
/// diagonal clamped to 1), λ starting at 1e-5, stop when one step changes the cost by less than 1e-5 of it.
/// Single-threaded: Ceres sums the cost and gradient per thread in an order that depends on scheduling.
ceres::Solver::Options solverOptions(const SolverOptions& options) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  o.jacobi_scaling = false;
  o.min_lm_diagonal = 1.0;
  o.max_lm_diagonal = 1.0;
  o.initial_trust_region_radius = 1e5;  // 1 / λ
  o.max_num_iterations = options.max_iterations;
  o.function_tolerance = 1e-5;
  o.gradient_tolerance = 1e-10;
  o.parameter_tolerance = 1e-10;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  return o;
}

}  // namespace

SolveResult solvePoseGraph(const jrl::PoseGraph& graph, const SolverOptions& options) {
  if (options.selection == FactorSelection::Inliers && !graph.has_outlier_labels)
    throw std::runtime_error(graph.name + ": no outlier labels (outlier_factors), so no inliers-only solve");
  SolveResult result;
  std::map<jrl::Key, PoseBlock> blocks;
  ceres::Problem problem;
  addFactors(graph, options, problem, blocks, result);

  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(options), &problem, &summary);

  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;  // iteration 0 is the initial state
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.termination = summary.message;
  for (const auto& [key, b] : blocks) result.poses[key] = b.pose();
  return result;
}

}  // namespace cosmo::backend
