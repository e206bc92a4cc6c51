// cosmo_jrl: dataset statistics (the paper's Fig. 1 metadata), invariant checks, figures, a back-end check and
// exports of JRL files.
//   cosmo_jrl stats [--json] FILE...
//   cosmo_jrl validate FILE...
//   cosmo_jrl plot FILE... [-o DIR] [--no-png]
//   cosmo_jrl solve FILE... [--json]
//   cosmo_jrl export FILE [--g2o OUT.g2o] [--tum DIR] [--labels OUT.csv]
//   cosmo_jrl inject IN.jrl OUT.jrl --rate R --kind random|local|group|mixed [--group-size K]
//             [--intra|--inter|--both] --seed N [--rate-of injected|all] [--outlier-rule fidelity|squared]
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/outlier_injection.hpp"
#include "cosmo/jrl/exports.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/report/figures.hpp"

namespace {

int usageError(const std::string& msg) {
  std::cerr << "cosmo_jrl: " << msg << "\nRun with --help for more information.\n";
  return 2;
}

struct Args {
  std::vector<std::string> files;
  bool json = false, no_png = false;
  std::string dir, g2o, tum, labels;  ///< plot -o; export --g2o, --tum, --labels
};

/// cosmo_jrl inject's words.
struct InjectArgs {
  std::string in, out, kind = "random", rate_of = "injected", rule = "fidelity";
  cosmo::dataset::InjectionParams p;
  CLI::Option *intra = nullptr, *inter = nullptr;
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
  return perFile(a.files, [&](const std::string& f) {
    for (const auto& p : cosmo::report::writeDatasetFigures(cosmo::jrl::readJrl(f), f, a.dir, !a.no_png))
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
  if (a.g2o.empty() && a.tum.empty() && a.labels.empty()) return usageError("export needs --g2o, --tum or --labels");
  return perFile(a.files, [&](const std::string& f) {
    const cosmo::jrl::Dataset d = cosmo::jrl::readJrl(f);
    if (!a.g2o.empty()) {
      for (const auto& p : cosmo::jrl::exportG2o(d, a.g2o)) std::cout << "wrote " << p << "\n";
    }
    if (!a.tum.empty())
      for (const auto& p : cosmo::jrl::exportTum(d, a.tum)) std::cout << "wrote " << p << "\n";
    if (!a.labels.empty()) {
      cosmo::jrl::exportLabelsCsv(d, a.labels);
      std::cout << "wrote " << a.labels << "\n";
    }
    return 0;
  });
}

/// Declares cosmo_jrl inject's options on its subcommand.
void addInject(CLI::App& app, InjectArgs& a) {
  app.add_option("IN", a.in, "input JRL (with ground truth and outlier labels)")->required()->check(CLI::ExistingFile);
  app.add_option("OUT", a.out, "output JRL (its name: the file stem)")->required();
  app.add_option("--rate", a.p.rate, "outlier rate in [0, 1)")->required()->check(CLI::Range(0.0, 0.999999));
  app.add_option("--kind", a.kind, "random | local | group | mixed")
      ->check(CLI::IsMember({"random", "local", "group", "mixed"}));
  app.add_option("--group-size", a.p.draw.group_size, "closures per group (group, mixed)")->check(CLI::Range(1, 1000));
  a.intra = app.add_flag("--intra", "pairs of poses of one robot only");
  a.inter = app.add_flag("--inter", "pairs of poses of two robots only");
  CLI::Option* both = app.add_flag("--both", "both (default; in the dataset's intra / inter proportion)");
  a.intra->excludes(a.inter)->excludes(both);
  a.inter->excludes(both);
  app.add_option("--seed", a.p.seed, "random seed (same seed, same output)")->required();
  app.add_option("--rate-of", a.rate_of, "injected (default) | all: what the rate counts")
      ->check(CLI::IsMember({"injected", "all"}));
  app.add_option("--outlier-rule", a.rule, "the dataset's label rule, which every injected closure fails")
      ->check(CLI::IsMember({"fidelity", "squared"}));
  app.add_option("--local-radius", a.p.draw.local_radius_m, "local: pose pairs at most this far apart (m)")
      ->check(cosmo::Positive);
}

int inject(InjectArgs a) {
  a.p.kind = *cosmo::dataset::parseOutlierKind(a.kind);
  a.p.scope = a.intra->count()   ? cosmo::dataset::ClosureScope::Intra
              : a.inter->count() ? cosmo::dataset::ClosureScope::Inter
                                 : cosmo::dataset::ClosureScope::Both;
  a.p.rate_of = a.rate_of == "all" ? cosmo::dataset::RateOf::All : cosmo::dataset::RateOf::Injected;
  a.p.draw.rule = *cosmo::dataset::parseOutlierRule(a.rule);
  try {
    cosmo::dataset::InjectionReport report;
    cosmo::jrl::Dataset d = cosmo::dataset::injectOutliers(cosmo::jrl::readJrl(a.in), a.p, &report);
    d.name = std::filesystem::path(a.out).stem().string();
    const auto violations = cosmo::jrl::validate(d);
    if (!violations.empty()) throw std::runtime_error(a.out + ": not written: " + violations.front().str());
    cosmo::jrl::writeJrl(a.out, d);
    std::cout << cosmo::dataset::formatInjection(report, a.p.kind) << "\nwrote " << a.out << "\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

/// The subcommands; the one given is parsed().
struct Commands {
  CLI::App *stats, *validate, *plot, *solve, *export_files, *inject;
};

/// stats, validate, plot and solve: their options and the files they read.
void declareReadCommands(CLI::App& app, Args& a, Commands& c) {
  const auto files = [&a](CLI::App* sub) { sub->add_option("FILE", a.files, "JRL files")->required(); };
  c.stats = app.add_subcommand(
      "stats",
      "per dataset: name, robots, duration (last minus first entry stamp, MM:SS), total length of the robots' "
      "ground-truth trajectories (km), intra-robot (LC) and inter-robot (IRLC) loop closures with the share listed "
      "in outlier_factors");
  c.stats->add_flag("--json", a.json, "one JSON object per line and dataset");
  files(c.stats);
  c.validate = app.add_subcommand(
      "validate",
      "checks unit quaternions, SPD covariances of the right size, non-decreasing stamps, factor keys present in "
      "groundtruth and initialization, outlier ids in range and outliers within potential outliers, an unbroken "
      "odometry chain; prints every violation with its place");
  files(c.validate);
  c.plot = app.add_subcommand(
      "plot",
      "writes <stem>.trajectories.svg (reference trajectories, loop closures: inliers solid, outliers dashed; "
      "metadata table) and <stem>.frontend.svg (odometry vs reference with keyframes; the measurements), and a .png "
      "of each when ImageMagick's `convert` is installed");
  c.plot->add_option("-o", a.dir, "output folder (default: the file's folder)")->type_name("DIR");
  c.plot->add_flag("--no-png", a.no_png, "SVG only");
  files(c.plot);
  c.solve = app.add_subcommand(
      "solve",
      "optimises the team's pose graph from the initialization (Ceres, Levenberg-Marquardt, sparse Cholesky): (1) "
      "all factors, least squares; (2) loop closures under a Cauchy kernel; (3) the labelled inliers only. Prints "
      "cost, iterations and the ATE (RMSE, no alignment) per robot and overall against the ground truth, and the "
      "initialization's");
  c.solve->add_flag("--json", a.json, "one object per line");
  files(c.solve);
}

/// export and inject: the commands that write files.
void declareWriteCommands(CLI::App& app, Args& a, InjectArgs& inject_args, Commands& c) {
  c.export_files = app.add_subcommand("export", "writes the dataset in other formats");
  c.export_files
      ->add_option("--g2o", a.g2o,
                   "one global graph (VERTEX_SE3:QUAT / EDGE_SE3:QUAT, ids in key order, information matrices "
                   "in g2o's convention), and beside it OUT.blocks.csv (robot,first_id,count: each robot's "
                   "contiguous ids) and OUT.ids.csv (g2o_id,robot,jrl_key,stamp: every vertex)")
      ->type_name("OUT.g2o");
  c.export_files->add_option("--tum", a.tum, "ground truth and initialization per robot as TUM files in DIR")
      ->type_name("DIR");
  c.export_files
      ->add_option("--labels", a.labels,
                   "every loop closure with its error against the ground truth, d^2 and label (CSV)")
      ->type_name("OUT.csv");
  c.export_files->add_option("FILE", a.files, "the JRL file")->required();
  c.inject = app.add_subcommand(
      "inject",
      "adds loop closures that are wrong by the kind's rule (docs/design.md, \"Injected outliers\"), each with the "
      "dataset's loop-closure covariance, in the entry where the front-end would have made it, listed in "
      "potential_outlier_factors and outlier_factors. Rate: the share of injected closures among the loop closures "
      "in scope after injection (--rate-of all: of every labelled outlier, natural ones included)");
  addInject(*c.inject, inject_args);
}

bool isCommand(CLI::App& app, const std::string& name) {
  try {
    app.get_subcommand(name);
    return true;
  } catch (const CLI::OptionNotFound&) { return false; }
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  InjectArgs inject_args;
  Commands c{};
  cosmo::CommandLine app(
      "cosmo_jrl",
      "Dataset statistics, invariant checks, figures, a back-end check and exports of JRL files. Exit code: 0 on "
      "success (validate: every file valid), 1 on invalid or unreadable files, 2 on usage errors.");
  app.require_subcommand(1);
  declareReadCommands(app, a, c);
  declareWriteCommands(app, a, inject_args, c);
  if (argc == 2 && std::string(argv[1]) == "help") {
    std::cout << app.help();
    return 0;
  }
  if (argc > 1 && argv[1][0] != '-' && !isCommand(app, argv[1]))
    return usageError(std::string("unknown command ") + argv[1]);
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  if (c.stats->parsed()) return stats(a);
  if (c.validate->parsed()) return validate(a);
  if (c.plot->parsed()) return plot(a);
  if (c.solve->parsed()) return solve(a);
  if (c.inject->parsed()) return inject(inject_args);
  return exportFiles(a);
}
