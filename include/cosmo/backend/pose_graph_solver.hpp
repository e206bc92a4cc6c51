#pragma once
// Batch optimisation of a team's whole Pose3 graph with Ceres (Levenberg-Marquardt with GTSAM's default damping and
// stopping rule, sparse normal Cholesky by CHOLMOD), from the dataset's initialization: the back-end check of
// `cosmo_jrl solve` and of the offline driver. Factors are those of jrl::poseGraph() with the error and analytic
// Jacobians of backend/pose_residual.hpp. Single-threaded: same input, same bytes.
#include <cstddef>
#include <string>

#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::backend {

enum class FactorSelection {
  All,        ///< every factor, least squares
  AllRobust,  ///< every factor; loop closures under a Cauchy kernel (priors and odometry are never outliers)
  Inliers,    ///< every factor not labelled an outlier (needs outlier labels), least squares
};

/// "all", "robust", "inliers".
const char* selectionName(FactorSelection selection);

/// Scale of the Cauchy kernel on whitened residuals: sqrt of the 95 % chi^2 value with 6 degrees of freedom,
/// i.e. a loop closure whose error is that many standard deviations of its own noise model keeps half its weight.
constexpr double kCauchyScale = 3.5485;

struct SolverOptions {
  FactorSelection selection = FactorSelection::Inliers;
  int max_iterations = 100;
  double cauchy_scale = kCauchyScale;
};

struct SolveResult {
  jrl::PoseMap poses;  ///< the optimised value of every key in the factors used
  std::size_t factors_used = 0;
  double initial_cost = 0.0;  ///< Ceres' cost 0.5 * sum rho(|whitened residual|^2) at the initialization
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;   ///< a convergence tolerance was met (not the iteration limit, not a failure)
  std::string termination;  ///< Ceres' message
};

/// Optimise `graph` from graph.initialization. Throws std::runtime_error when a key has no initialization, a
/// covariance is not positive definite, or Inliers is asked of a graph without outlier labels.
SolveResult solvePoseGraph(const jrl::PoseGraph& graph, const SolverOptions& options);

}  // namespace cosmo::backend
