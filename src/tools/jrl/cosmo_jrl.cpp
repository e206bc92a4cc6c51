// cosmo_jrl: dataset statistics (the paper's Fig. 1 metadata), invariant checks, figures, a back-end check and
// exports of JRL files.
//   cosmo_jrl stats [--json] FILE...
//   cosmo_jrl validate FILE...
//   cosmo_jrl plot FILE... [-o DIR] [--no-png]
//   cosmo_jrl solve FILE... [--json]
//   cosmo_jrl export FILE [--g2o OUT.g2o] [--tum DIR] [--labels OUT.csv]
//   cosmo_jrl inject IN.jrl OUT.jrl --rate R --kind random|local|group|mixed [--group-size K]
//             [--intra|--inter|--both] --seed N [--rate-of injected|all] [--outlier-rule fidelity|squared]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/dataset/outlier_injection.hpp"
#include "cosmo/jrl/exports.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/report/figures.hpp"

namespace {

const char* kUsage =
    "usage: cosmo_jrl stats [--json] FILE...\n"
    "       cosmo_jrl validate FILE...\n"
    "       cosmo_jrl plot [-o DIR] [--no-png] FILE...\n"
    "       cosmo_jrl solve [--json] FILE...\n"
    "       cosmo_jrl export FILE [--g2o OUT.g2o] [--tum DIR] [--labels OUT.csv]\n"
    "       cosmo_jrl inject IN.jrl OUT.jrl --rate R --kind random|local|group|mixed [--group-size K]\n"
    "                 [--intra|--inter|--both] --seed N [--rate-of injected|all] [--outlier-rule fidelity|squared]\n"
    "       cosmo_jrl --help\n"
    "\n"
    "stats     per dataset: name, robots, duration (last minus first entry stamp, MM:SS), total length of the\n"
    "          robots' ground-truth trajectories (km), intra-robot (LC) and inter-robot (IRLC) loop closures\n"
    "          with the share listed in outlier_factors. --json: one JSON object per line and dataset.\n"
    "validate  checks unit quaternions, SPD covariances of the right size, non-decreasing stamps, factor keys\n"
    "          present in groundtruth and initialization, outlier ids in range and outliers within potential\n"
    "          outliers, an unbroken odometry chain; prints every violation with its place.\n"
    "plot      writes <stem>.trajectories.svg (reference trajectories, loop closures: inliers solid, outliers\n"
    "          dashed; metadata table) and <stem>.frontend.svg (odometry vs reference with keyframes; the\n"
    "          measurements) into DIR (default: the file's folder), and a .png of each when ImageMagick's\n"
    "          `convert` is installed (unless --no-png).\n"
    "solve     optimises the team's pose graph from the initialization (Ceres, Levenberg-Marquardt, sparse\n"
    "          Cholesky): (1) all factors, least squares; (2) loop closures under a Cauchy kernel; (3) the\n"
    "          labelled inliers only. Prints cost, iterations and the ATE (RMSE, no alignment) per robot and\n"
    "          overall against the ground truth, and the initialization's. --json: one object per line.\n"
    "export    --g2o: one global graph (VERTEX_SE3:QUAT / EDGE_SE3:QUAT, ids in key order, information\n"
    "          matrices in g2o's convention); --tum: ground truth and initialization per robot as TUM files in DIR;\n"
    "          --labels: every loop closure with its error against the ground truth, d^2 and label (CSV).\n"
    "inject    adds loop closures that are wrong by the kind's rule, labelled outliers (cosmo_jrl inject --help).\n"
    "\n"
    "exit code: 0 on success (validate: every file valid), 1 on invalid or unreadable files, 2 on usage errors\n";

int usageError(const std::string& msg) {
  std::cerr << "cosmo_jrl: " << msg << "\n" << kUsage;
  return 2;
}

struct Args {
  std::string cmd;
  std::vector<std::string> files;
  bool json = false, png = true;
  std::map<std::string, std::string> values;  ///< -o, --g2o, --tum, --labels
};

/// Runs `body` per file; errors name the file's problem and make the exit code 1.
template <typename F>
int perFile(const std::vector<std::string>& files, F body) {
  int rc = 0;
  for (const auto& f : files) {
    try {
      rc = std::max(rc, body(f));
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      rc = 1;
    }
  }
  return rc;
}

int stats(const Args& a) {
  bool first = true;
  return perFile(a.files, [&](const std::string& f) {
    const auto s = cosmo::jrl::computeStats(cosmo::jrl::readJrl(f));
    if (a.json) {
      std::cout << cosmo::jrl::statsJson(s) << "\n";
    } else {
      if (!first) std::cout << "\n";
      std::cout << cosmo::jrl::formatStats(s);
    }
    first = false;
    return 0;
  });
}

int validate(const Args& a) {
  int rc = 0;
  for (const auto& f : a.files) {
    try {
      const auto violations = cosmo::jrl::validate(cosmo::jrl::readJrl(f));
      if (violations.empty()) {
        std::cout << f << ": OK\n";
        continue;
      }
      rc = 1;
      for (const auto& v : violations) std::cout << f << ": " << v.str() << "\n";
      std::cout << f << ": " << violations.size() << " violation(s)\n";
    } catch (const std::exception& e) {
      std::cout << "error: " << e.what() << "\n";
      rc = 1;
    }
  }
  return rc;
}

int plot(const Args& a) {
  const auto dir = a.values.count("-o") ? a.values.at("-o") : std::string();
  return perFile(a.files, [&](const std::string& f) {
    for (const auto& p : cosmo::report::writeDatasetFigures(cosmo::jrl::readJrl(f), f, dir, a.png))
      std::cout << "wrote " << p << "\n";
    return 0;
  });
}

int solve(const Args& a) {
  using cosmo::backend::FactorSelection;
  return perFile(a.files, [&](const std::string& f) {
    const cosmo::jrl::Dataset d = cosmo::jrl::readJrl(f);
    std::vector<FactorSelection> selections{FactorSelection::All, FactorSelection::AllRobust};
    if (d.outliers) selections.push_back(FactorSelection::Inliers);
    const auto check = cosmo::backend::checkDataset(d, selections);
    if (a.json)
      std::cout << cosmo::backend::checkJson(check) << "\n";
    else
      std::cout << cosmo::backend::formatCheck(check)
                << (d.outliers ? "" : "  (no outlier labels: no inliers solve)\n");
    return 0;
  });
}

int exportFiles(const Args& a) {
  if (a.files.size() != 1) return usageError("export takes one FILE");
  if (!a.values.count("--g2o") && !a.values.count("--tum") && !a.values.count("--labels"))
    return usageError("export needs --g2o, --tum or --labels");
  return perFile(a.files, [&](const std::string& f) {
    const cosmo::jrl::Dataset d = cosmo::jrl::readJrl(f);
    if (a.values.count("--g2o")) {
      cosmo::jrl::exportG2o(d, a.values.at("--g2o"));
      std::cout << "wrote " << a.values.at("--g2o") << "\n";
    }
    if (a.values.count("--tum"))
      for (const auto& p : cosmo::jrl::exportTum(d, a.values.at("--tum"))) std::cout << "wrote " << p << "\n";
    if (a.values.count("--labels")) {
      cosmo::jrl::exportLabelsCsv(d, a.values.at("--labels"));
      std::cout << "wrote " << a.values.at("--labels") << "\n";
    }
    return 0;
  });
}

/// cosmo_jrl inject: its own options (CLI11); `args` are the words after "inject".
int inject(std::vector<std::string> args) {
  CLI::App app{
      "Adds loop closures that are wrong by the kind's rule (docs/design.md, \"Injected outliers\"), each with the "
      "dataset's loop-closure covariance, in the entry where the front-end would have made it, listed in "
      "potential_outlier_factors and outlier_factors. Rate: the share of injected closures among the loop closures "
      "in scope after injection (--rate-of all: of every labelled outlier, natural ones included).",
      "cosmo_jrl inject"};
  std::string in, out, kind = "random", rate_of = "injected", rule = "fidelity";
  cosmo::InjectionParams p;
  app.add_option("IN", in, "input JRL (with ground truth and outlier labels)")->required()->check(CLI::ExistingFile);
  app.add_option("OUT", out, "output JRL (its name: the file stem)")->required();
  app.add_option("--rate", p.rate, "outlier rate in [0, 1)")->required()->check(CLI::Range(0.0, 0.999999));
  app.add_option("--kind", kind, "random | local | group | mixed")
      ->check(CLI::IsMember({"random", "local", "group", "mixed"}));
  app.add_option("--group-size", p.draw.group_size, "closures per group (group, mixed)")->check(CLI::Range(1, 1000));
  auto* intra = app.add_flag("--intra", "pairs of poses of one robot only");
  auto* inter = app.add_flag("--inter", "pairs of poses of two robots only");
  auto* both = app.add_flag("--both", "both (default; in the dataset's intra / inter proportion)");
  intra->excludes(inter)->excludes(both);
  inter->excludes(both);
  app.add_option("--seed", p.seed, "random seed (same seed, same output)")->required();
  app.add_option("--rate-of", rate_of, "injected (default) | all: what the rate counts")
      ->check(CLI::IsMember({"injected", "all"}));
  app.add_option("--outlier-rule", rule, "the dataset's label rule, which every injected closure fails")
      ->check(CLI::IsMember({"fidelity", "squared"}));
  app.add_option("--local-radius", p.draw.local_radius_m, "local: pose pairs at most this far apart (m)")
      ->check(CLI::PositiveNumber);
  std::reverse(args.begin(), args.end());  // CLI11 takes a vector in reverse order
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  p.kind = *cosmo::parseOutlierKind(kind);
  p.scope = intra->count() ? cosmo::ClosureScope::Intra
                           : inter->count() ? cosmo::ClosureScope::Inter : cosmo::ClosureScope::Both;
  p.rate_of = rate_of == "all" ? cosmo::RateOf::All : cosmo::RateOf::Injected;
  p.draw.rule = *cosmo::parseOutlierRule(rule);
  try {
    cosmo::InjectionReport report;
    cosmo::jrl::Dataset d = cosmo::injectOutliers(cosmo::jrl::readJrl(in), p, &report);
    d.name = std::filesystem::path(out).stem().string();
    const auto violations = cosmo::jrl::validate(d);
    if (!violations.empty()) throw std::runtime_error(out + ": not written: " + violations.front().str());
    cosmo::jrl::writeJrl(out, d);
    std::cout << cosmo::formatInjection(report, p.kind) << "\nwrote " << out << "\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return usageError("missing command");
  if (args[0] == "inject") return inject({args.begin() + 1, args.end()});
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kUsage;
    return 0;
  }
  Args a;
  a.cmd = args[0];
  const std::map<std::string, std::vector<std::string>> valued{{"plot", {"-o"}},
                                                               {"export", {"--g2o", "--tum", "--labels"}}};
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& s = args[i];
    const auto v = valued.find(a.cmd);
    if (s == "--help" || s == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (s == "--json" && (a.cmd == "stats" || a.cmd == "solve")) {
      a.json = true;
    } else if (s == "--no-png" && a.cmd == "plot") {
      a.png = false;
    } else if (v != valued.end() && std::find(v->second.begin(), v->second.end(), s) != v->second.end()) {
      if (i + 1 >= args.size()) return usageError(s + " needs a value");
      a.values[s] = args[++i];
    } else if (s.size() > 1 && s[0] == '-') {
      return usageError("unknown option " + s);
    } else {
      a.files.push_back(s);
    }
  }
  if (a.files.empty() && a.cmd != "--help") {
    if (a.cmd == "stats" || a.cmd == "validate" || a.cmd == "plot" || a.cmd == "solve" || a.cmd == "export")
      return usageError("no FILE given");
  }
  if (a.cmd == "stats") return stats(a);
  if (a.cmd == "validate") return validate(a);
  if (a.cmd == "plot") return plot(a);
  if (a.cmd == "solve") return solve(a);
  if (a.cmd == "export") return exportFiles(a);
  return usageError("unknown command " + a.cmd);
}
