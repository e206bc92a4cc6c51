// cosmo_jrl: dataset statistics (the paper's Fig. 1 metadata) and invariant checks of JRL files.
//   cosmo_jrl stats [--json] FILE...
//   cosmo_jrl validate FILE...
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"

namespace {

const char* kUsage =
    "usage: cosmo_jrl stats [--json] FILE...\n"
    "       cosmo_jrl validate FILE...\n"
    "       cosmo_jrl --help\n"
    "\n"
    "stats     per dataset: name, robots, duration (last minus first entry stamp, MM:SS), total length of the\n"
    "          robots' ground-truth trajectories (km), intra-robot (LC) and inter-robot (IRLC) loop closures\n"
    "          with the share listed in outlier_factors. --json: one JSON object per line and dataset.\n"
    "validate  checks unit quaternions, SPD covariances of the right size, non-decreasing stamps, factor keys\n"
    "          present in groundtruth and initialization, outlier ids in range and outliers within potential\n"
    "          outliers, an unbroken odometry chain; prints every violation with its place.\n"
    "\n"
    "exit code: 0 on success (validate: every file valid), 1 on invalid or unreadable files, 2 on usage errors\n";

int usageError(const std::string& msg) {
  std::cerr << "cosmo_jrl: " << msg << "\n" << kUsage;
  return 2;
}

int stats(const std::vector<std::string>& files, bool json) {
  int rc = 0;
  bool first = true;
  for (const auto& f : files) {
    try {
      const auto s = cosmo::jrl::computeStats(cosmo::jrl::readJrl(f));
      if (json) {
        std::cout << cosmo::jrl::statsJson(s) << "\n";
      } else {
        if (!first) std::cout << "\n";
        std::cout << cosmo::jrl::formatStats(s);
      }
      first = false;
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      rc = 1;
    }
  }
  return rc;
}

int validate(const std::vector<std::string>& files) {
  int rc = 0;
  for (const auto& f : files) {
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

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return usageError("missing command");
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kUsage;
    return 0;
  }
  const std::string cmd = args[0];
  bool json = false;
  std::vector<std::string> files;
  for (std::size_t i = 1; i < args.size(); ++i) {
    if (args[i] == "--help" || args[i] == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (args[i] == "--json" && cmd == "stats")
      json = true;
    else if (args[i].size() > 1 && args[i][0] == '-')
      return usageError("unknown option " + args[i]);
    else
      files.push_back(args[i]);
  }
  if (cmd != "stats" && cmd != "validate") return usageError("unknown command " + cmd);
  if (files.empty()) return usageError("no FILE given");
  return cmd == "stats" ? stats(files, json) : validate(files);
}
