#pragma once
// A temporary folder with small sequence configs (their "bags" are placeholder files, their references TUM files
// of a given length), suite files and a report's jobs and records, for the suite module's tests: nothing here runs a
// program.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cosmo/suite/job_record.hpp"
#include "cosmo/suite/plan.hpp"

namespace suite_test {

namespace fs = std::filesystem;

struct Folder {
  fs::path root;
  Folder() : root(fs::temp_directory_path() / ("cosmo_suite_test_" + std::to_string(::getpid()) + "_" + next())) {
    fs::create_directories(root);
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  static std::string next() {
    static int n = 0;
    return std::to_string(n++);
  }
  fs::path write(const std::string& rel, const std::string& text) const {
    const fs::path p = root / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
};

/// A sequence config `<name>.yaml` in `dir` with `robots` trials of `seconds` each (TUM references at 10 Hz).
inline fs::path writeSequence(const Folder& f, const std::string& dir, const std::string& name, int robots,
                              double seconds, const std::string& extra = "environment: synthetic\n") {
  std::string yaml = "name: " + name + "\nseed: 3\n" + extra + "trials:\n";
  for (int i = 0; i < robots; ++i) {
    const char r = static_cast<char>('a' + i);
    const std::string trial = name + "_" + r;
    f.write(dir + "/" + trial + ".bag", "not a bag: the tests do not run it\n");
    std::string tum;
    for (int k = 0; k <= static_cast<int>(seconds * 10); ++k)
      tum += std::to_string(1.7e9 + 0.1 * k) + " " + std::to_string(k * 0.1) + " 0 0 0 0 0 1\n";
    f.write(dir + "/" + trial + ".txt", tum);
    yaml += std::string("  - robot: ") + r + "\n    name: " + trial + "\n    bag: " + trial + ".bag\n    reference: " +
            trial + ".txt\n";
  }
  return f.write(dir + "/" + name + ".yaml", yaml);
}

inline cosmo::suite::PlanOptions planOptions(const Folder& f) {
  f.write("cosmo_generate", "a program\n");
  f.write("cosmo_jrl", "another program\n");
  cosmo::suite::PlanOptions o;
  o.out_dir = (f.root / "out").string();
  o.program_dir = f.root.string();
  o.default_config_dir = std::string(COSMO_SOURCE_DIR) + "/config";
  o.simulate = [](const cosmo::suite::SequenceEntry&) -> std::string { throw std::runtime_error("no simulation"); };
  return o;
}

/// A group job of the paper sequence tuhh_r3_01 with both comm models, for the report's tests.
inline cosmo::suite::Job group(const std::string& id, const std::string& label) {
  cosmo::suite::Job j;
  j.id = id;
  j.label = label;
  j.sequence_name = "tuhh_r3_01";
  j.comms = {"wifi", "proradio"};
  return j;
}

/// Its record: two datasets (wifi, proradio) with `lc` loop closures and an inliers-solve ATE of `ate`.
inline cosmo::suite::JobRecord record(const std::string& id, std::size_t lc, double ate) {
  cosmo::suite::JobRecord r;
  r.job = id;
  r.wall_s = 730;
  r.cpu_s = 1400;
  r.peak_rss_mb = 512;
  for (const char* comm : {"wifi", "proradio"}) {
    cosmo::suite::DatasetSummary d;
    d.name = id + "_" + comm;
    d.comm = comm;
    d.duration_s = 727.2;
    d.length_m = 2150;
    d.lc = lc;
    d.lc_outliers = lc / 10;
    d.irlc = 300;
    d.irlc_outliers = 30;
    d.inliers_ate_m = ate;
    d.init_ate_m = 25.7;
    r.datasets.push_back(d);
  }
  return r;
}

}  // namespace suite_test
