// Robust solve against injected outliers (dataset/outlier_injection.hpp): for each kind and rate, the dataset with
// that many injected closures solved with the Cauchy kernel on the loop closures (`cosmo_jrl solve`'s robust solve),
// ATE (RMSE, no alignment, all robots' own poses) against the ground truth, over several seeds.
//   bench_outlier_sweep FILE.jrl [--rates 0.1,0.2,0.3,0.5] [--kinds random,local,group,mixed] [--seeds 3]
//                       [--group-size 5]
// Prints a markdown table (mean and range over the seeds) and the labelled inliers' ATE, which injection leaves as it
// is.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "cosmo/backend/pose_graph_solver.hpp"
#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/dataset/outlier_injection.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/trajectory_error.hpp"

using namespace cosmo;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

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
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::fprintf(stderr, "usage: bench_outlier_sweep FILE.jrl [--rates LIST] [--kinds LIST] [--seeds N] [--group-size K]\n");
    return argc < 2 ? 2 : 0;
  }
  std::vector<std::string> rates{"0.1", "0.2", "0.3", "0.5"}, kinds{"random", "local", "group", "mixed"};
  int seeds = 3;
  std::size_t group_size = 5;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--rates") rates = split(v);
    else if (a == "--kinds") kinds = split(v);
    else if (a == "--seeds") seeds = std::atoi(v.c_str());
    else if (a == "--group-size") group_size = static_cast<std::size_t>(std::atoi(v.c_str()));
    else {
      std::fprintf(stderr, "bench_outlier_sweep: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const jrl::Dataset in = jrl::readJrl(argv[1]);
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
        InjectionParams p;
        p.rate = std::stod(rate);
        p.kind = *parseOutlierKind(kind);
        p.seed = static_cast<std::uint64_t>(s);
        p.draw.group_size = group_size;
        InjectionReport report;
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
