// Robust solve against injected outliers (dataset/outlier_injection.hpp): for each kind and rate, the dataset with
// that many injected closures solved with the Cauchy kernel on the loop closures (`cosmo_jrl solve`'s robust solve),
// ATE (RMSE, no alignment, all robots' own poses) against the ground truth, over several seeds.
//   bench_outlier_sweep FILE.jrl [--rates 0.1,0.2,0.3,0.5] [--kinds random,local,group,mixed] [--seeds 3]
//                       [--group-size 5]
// Prints a markdown table (mean and range over the seeds) and the labelled inliers' ATE, which injection leaves as it
// is.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/backend/pose_graph_solver.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/outlier_injection.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/trajectory_error.hpp"

using namespace cosmo;

namespace {

double ate(const jrl::Dataset& d, backend::FactorSelection selection, int* iterations = nullptr) {
  const jrl::PoseGraph g = jrl::poseGraph(d);
  backend::SolverOptions o;
  o.selection = selection;
  const backend::SolveResult r = backend::solvePoseGraph(g, o);
  if (iterations) *iterations = r.iterations;
  return jrl::trajectoryError(g.robots, r.poses, g.groundtruth).overall.trans_m;
}

}  // namespace

int main(int argc, char** argv) {
  std::string file;
  std::vector<std::string> rates{"0.1", "0.2", "0.3", "0.5"}, kinds{"random", "local", "group", "mixed"};
  int seeds = 3;
  std::size_t group_size = 5;
  CommandLine app("bench_outlier_sweep",
                  "Robust solve against injected outliers: per kind and rate, the dataset's robust ATE over several "
                  "seeds (a markdown table), and the labelled inliers' ATE.");
  app.add_option("FILE.jrl", file, "the dataset")->required();
  app.add_option("--rates", rates, "outlier rates, comma separated")->delimiter(',')->capture_default_str();
  app.add_option("--kinds", kinds, "outlier kinds, comma separated")->delimiter(',')->capture_default_str();
  app.add_option("--seeds", seeds, "seeds 1..N per cell")->capture_default_str();
  app.add_option("--group-size", group_size, "closures per group (group, mixed)")->capture_default_str();
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  const jrl::Dataset in = jrl::readJrl(file);
  bench::Stopwatch total;
  std::printf("%s: inliers ATE %.3f m, robust ATE %.3f m (as released / generated)\n\n", in.name.c_str(),
              ate(in, backend::FactorSelection::Inliers), ate(in, backend::FactorSelection::AllRobust));
  std::printf("| rate |");
  for (const auto& k : kinds) std::printf(" %s |", k.c_str());
  std::printf("\n|---|");
  for (std::size_t i = 0; i < kinds.size(); ++i) std::printf("---|");
  std::printf("\n");
  for (const auto& rate : rates) {
    std::printf("| %s |", rate.c_str());
    for (const auto& kind : kinds) {
      std::vector<double> values;
      std::size_t injected = 0;
      for (int s = 1; s <= seeds; ++s) {
        dataset::InjectionParams p;
        p.rate = std::stod(rate);
        p.kind = *dataset::parseOutlierKind(kind);
        p.seed = static_cast<std::uint64_t>(s);
        p.draw.group_size = group_size;
        dataset::InjectionReport report;
        values.push_back(ate(injectOutliers(in, p, &report), backend::FactorSelection::AllRobust));
        injected = report.injected;
      }
      double mean = 0.0;
      for (double v : values) mean += v / static_cast<double>(values.size());
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      std::printf(" %.3f (%.3f–%.3f; +%zu) |", mean, *lo, *hi, injected);
      std::fflush(stdout);
    }
    std::printf("\n");
  }
  std::printf("\nrobust ATE (m), mean (range) over seeds 1..%d, +N injected closures; %.1f s wall\n", seeds,
              total.elapsedMs() / 1000.0);
  return 0;
}
