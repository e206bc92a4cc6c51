// cosmo_jrl: dataset statistics (the paper's Fig. 1 metadata), invariant checks, figures, a back-end check and
// exports of JRL files.
//   cosmo_jrl stats [--json] FILE...
//   cosmo_jrl validate FILE...
//   cosmo_jrl plot FILE... [-o DIR] [--no-png]
//   cosmo_jrl solve FILE... [--json]
//   cosmo_jrl export FILE [--g2o OUT.g2o] [--tum DIR] [--labels OUT.csv]
#include <algorithm>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "cosmo/backend/dataset_check.hpp"
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

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return usageError("missing command");
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
