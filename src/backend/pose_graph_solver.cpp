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

/// A pose as Ceres parameter blocks: quaternion [x, y, z, w] and translation.
struct PoseBlock {
  Eigen::Quaterniond q;
  Eigen::Vector3d t;
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

PoseBlock& blockOf(std::map<jrl::Key, PoseBlock>& blocks, const jrl::PoseGraph& graph, jrl::Key key,
                   ceres::Problem& problem, ceres::Manifold* quaternion) {
  auto it = blocks.find(key);
  if (it != blocks.end()) return it->second;
  const auto init = graph.initialization.find(key);
  if (init == graph.initialization.end()) throw std::runtime_error("no initialization of pose " + jrl::keyName(key));
  PoseBlock& b = blocks[key];
  b.q = Eigen::Quaterniond(init->second.linear()).normalized();
  b.t = init->second.translation();
  problem.AddParameterBlock(b.q.coeffs().data(), 4, quaternion);
  problem.AddParameterBlock(b.t.data(), 3);
  return b;
}

void addFactors(const jrl::PoseGraph& graph, const SolverOptions& options, ceres::Problem& problem,
                std::map<jrl::Key, PoseBlock>& blocks, SolveResult& result) {
  auto* quaternion = new ceres::EigenQuaternionManifold;  // owned by the problem
  for (const jrl::PoseFactor& f : graph.factors) {
    if (!selected(f, options.selection)) continue;
    checkCovariance(f);
    PoseBlock& b1 = blockOf(blocks, graph, f.key1, problem, quaternion);
    if (f.kind == jrl::FactorKind::Prior) {
      problem.AddResidualBlock(PriorResidual::create(f.measured, f.covariance), nullptr, b1.q.coeffs().data(),
                               b1.t.data());
    } else {
      PoseBlock& b2 = blockOf(blocks, graph, f.key2, problem, quaternion);
      ceres::LossFunction* loss = options.selection == FactorSelection::AllRobust && f.isLoopClosure()
                                      ? new ceres::CauchyLoss(options.cauchy_scale)
                                      : nullptr;
      problem.AddResidualBlock(BetweenResidual::create(f.measured, f.covariance), loss, b1.q.coeffs().data(),
                               b1.t.data(), b2.q.coeffs().data(), b2.t.data());
    }
    ++result.factors_used;
  }
}

ceres::Solver::Options solverOptions(const SolverOptions& options) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.max_num_iterations = options.max_iterations;
  o.function_tolerance = 1e-10;
  o.gradient_tolerance = 1e-12;
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
  for (const auto& [key, b] : blocks) result.poses[key] = makePose(b.t, b.q);
  return result;
}

}  // namespace cosmo::backend
