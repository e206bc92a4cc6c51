#include "cosmo/backend/dataset_check.hpp"

#include <cmath>
#include <cstdio>
#include <future>
#include <sstream>

#include <nlohmann/json.hpp>

namespace cosmo::backend {

namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

/// Rounded for JSON (stable text, no noise digits).
double rounded(double v, double per_unit) { return std::round(v * per_unit) / per_unit; }

void errorRow(std::ostringstream& out, const std::string& label, const jrl::TrajectoryError& e,
              const std::vector<char>& robots) {
  out << "  " << label;
  for (std::size_t i = label.size(); i < 10; ++i) out << ' ';
  out << "ATE " << fixed(e.overall.trans_m, 3) << " m, rot " << fixed(e.overall.rot_rad * kDeg, 2) << " deg |";
  for (char r : robots) {
    const auto& p = e.robots.at(r);
    out << ' ' << r << ' ' << fixed(p.trans_m, 3) << " m " << fixed(p.rot_rad * kDeg, 2) << " deg";
  }
  out << "\n";
}

nlohmann::json errorJson(const jrl::PoseErrorRmse& e) {
  return {{"ate_m", rounded(e.trans_m, 1e6)}, {"rot_rmse_deg", rounded(e.rot_rad * kDeg, 1e6)}};
}

SelectionCheck solveAndMeasure(const jrl::PoseGraph& graph, FactorSelection selection) {
  SolverOptions options;
  options.selection = selection;
  SelectionCheck c;
  c.selection = selection;
  c.solve = solvePoseGraph(graph, options);
  c.error = jrl::trajectoryError(graph.robots, c.solve.poses, graph.groundtruth);
  return c;
}

}  // namespace

DatasetCheck checkDataset(const jrl::Dataset& dataset, const std::vector<FactorSelection>& selections) {
  const jrl::PoseGraph graph = jrl::poseGraph(dataset);
  if (graph.groundtruth.empty()) throw std::runtime_error(dataset.name + ": no ground truth to measure the ATE");
  if (graph.initialization.empty()) throw std::runtime_error(dataset.name + ": no initialization to solve from");
  DatasetCheck check;
  check.name = dataset.name;
  check.robots = dataset.robots;
  check.poses = graph.initialization.size();
  check.factors = graph.factors.size();
  check.init = jrl::trajectoryError(graph.robots, graph.initialization, graph.groundtruth);
  std::vector<std::future<SelectionCheck>> runs;
  for (FactorSelection s : selections)
    runs.push_back(std::async(std::launch::async, [&graph, s] { return solveAndMeasure(graph, s); }));
  for (auto& run : runs) check.solves.push_back(run.get());
  return check;
}

std::string formatCheck(const DatasetCheck& check) {
  std::ostringstream out;
  out << check.name << ": " << check.poses << " poses, " << check.factors << " factors (ATE: RMSE over each robot's "
      << "own poses, no alignment)\n";
  errorRow(out, "init", check.init, check.robots);
  for (const auto& c : check.solves) {
    errorRow(out, selectionName(c.selection), c.error, check.robots);
    out << "            " << c.solve.factors_used << " factors, cost " << fixed(c.solve.initial_cost, 1) << " -> "
        << fixed(c.solve.final_cost, 1) << ", " << c.solve.iterations << " iterations"
        << (c.solve.converged ? "" : " (not converged: " + c.solve.termination + ")") << "\n";
  }
  return out.str();
}

std::string checkJson(const DatasetCheck& check) {
  nlohmann::json j;
  j["name"] = check.name;
  j["poses"] = check.poses;
  j["factors"] = check.factors;
  auto put = [&](nlohmann::json& obj, const std::string& prefix, const jrl::PoseErrorRmse& e) {
    const nlohmann::json v = errorJson(e);
    obj[prefix + "_ate_m"] = v["ate_m"];
    obj[prefix + "_rot_rmse_deg"] = v["rot_rmse_deg"];
  };
  nlohmann::json robots = nlohmann::json::object();
  put(j, "init", check.init.overall);
  for (char r : check.robots) put(robots[std::string(1, r)], "init", check.init.robots.at(r));
  for (const auto& c : check.solves) {
    const std::string p = selectionName(c.selection);
    put(j, p, c.error.overall);
    j[p + "_cost"] = rounded(c.solve.final_cost, 1e6);
    j[p + "_initial_cost"] = rounded(c.solve.initial_cost, 1e6);
    j[p + "_iterations"] = c.solve.iterations;
    j[p + "_converged"] = c.solve.converged;
    j[p + "_factors"] = c.solve.factors_used;
    for (char r : check.robots) put(robots[std::string(1, r)], p, c.error.robots.at(r));
  }
  j["robots"] = robots;
  return j.dump();
}

std::string inliersSolveLine(const jrl::Dataset& dataset) {
  if (!dataset.outliers) return "inliers solve: skipped (the dataset has no outlier labels)";
  try {
    const DatasetCheck check = checkDataset(dataset, {FactorSelection::Inliers});
    const double ate = check.solves.front().error.overall.trans_m, init = check.init.overall.trans_m;
    std::string line = "inliers solve to ATE " + fixed(ate, 3) + " m (init " + fixed(init, 3) + " m)";
    if (ate > init)
      line += "; SUSPICIOUS: the labelled inliers pull the team further from the ground truth than odometry alone";
    return line;
  } catch (const std::exception& e) { return std::string("inliers solve: skipped (") + e.what() + ")"; }
}

}  // namespace cosmo::backend
