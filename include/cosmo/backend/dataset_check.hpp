#pragma once
// The back-end check of a dataset (`cosmo_jrl solve`, and the offline driver's one line): the team's pose graph
// solved from its initialization (1) with all factors, least squares, (2) with a robust kernel on the loop
// closures, (3) with the labelled inliers only; for each and for the initialization itself the position and
// rotation ATE against the ground truth (jrl/trajectory_error.hpp: per robot, no alignment).
// A sound dataset's inliers solve to well below its initialization's ATE.
#include <string>
#include <vector>

#include "cosmo/backend/pose_graph_solver.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/jrl/trajectory_error.hpp"

namespace cosmo::backend {

struct SelectionCheck {
  FactorSelection selection = FactorSelection::All;
  SolveResult solve;  ///< poses included
  jrl::TrajectoryError error;
};

struct DatasetCheck {
  std::string name;
  std::vector<char> robots;
  std::size_t poses = 0, factors = 0;
  jrl::TrajectoryError init;
  std::vector<SelectionCheck> solves;  ///< in the order asked
};

/// Solves `dataset` once per selection, the selections in parallel threads (each solve is single-threaded and
/// independent, so the results do not depend on the scheduling). Throws std::runtime_error when the dataset has no
/// ground truth or no initialization, or as solvePoseGraph() does (Inliers without outlier labels).
DatasetCheck checkDataset(const jrl::Dataset& dataset, const std::vector<FactorSelection>& selections);

/// A readable table: per solve its cost, iterations and ATE per robot and overall, and the initialization's.
std::string formatCheck(const DatasetCheck& check);
/// One JSON object: name, poses, factors, init_ate_m, init_rot_rmse_deg, <sel>_ate_m, <sel>_rot_rmse_deg,
/// <sel>_cost, <sel>_initial_cost, <sel>_iterations, <sel>_converged for each selection (all, robust, inliers),
/// and "robots": {"a": {same ATE fields}, ...}.
std::string checkJson(const DatasetCheck& check);

/// The offline driver's line: "inliers solve to ATE x m (init y m)", followed by "; SUSPICIOUS: ..." when the
/// inliers solve to more than the initialization's ATE; or why there is no such solve (no labels, no ground
/// truth). Never throws.
std::string inliersSolveLine(const jrl::Dataset& dataset);

}  // namespace cosmo::backend
