// Read / write times of JRL files: the reference COSMO-Bench file (when ../shared exists) and a ~4 MB
// synthetic COSMO-like dataset. Target (issue 2): each well under a second.
//   bench_jrl_io [--repeats N] [--poses N] [--keep DIR]
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/synthetic.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;
using cosmo::bench::Stopwatch;

namespace {

struct Times {
  std::vector<double> read_ms, parse_ms, dump_ms, write_ms;
};

void measure(const std::string& label, const std::string& path, int repeats, const std::string& out_dir) {
  Times t;
  bool identical = true;
  std::size_t bytes = 0;
  for (int i = 0; i < repeats; ++i) {
    Stopwatch sw;
    const cosmo::jrl::Dataset d = cosmo::jrl::readJrl(path);
    t.read_ms.push_back(sw.elapsedMs());
    const std::string text = cosmo::readWholeFileOrEmpty(path);
    bytes = text.size();
    sw.restart();
    const cosmo::jrl::Dataset d2 = cosmo::jrl::parseJrl(text, path);
    t.parse_ms.push_back(sw.elapsedMs());
    sw.restart();
    const std::string dumped = cosmo::jrl::dumpJrl(d2);
    t.dump_ms.push_back(sw.elapsedMs());
    identical = identical && dumped == text;
    const std::string out = out_dir + "/bench_out.jrl";
    sw.restart();
    cosmo::jrl::writeJrl(out, d);
    t.write_ms.push_back(sw.elapsedMs());
  }
  auto med = [](const std::vector<double>& v) { return cosmo::bench::quantile(v, 0.5); };
  auto mx = [](const std::vector<double>& v) { return cosmo::bench::quantile(v, 1.0); };
  std::printf(
      "%-28s %9.2f MB  read %7.1f ms (max %7.1f)  parse %7.1f ms  dump %7.1f ms  write %7.1f ms (max %7.1f)  "
      "round trip %s\n",
      label.c_str(), double(bytes) / 1e6, med(t.read_ms), mx(t.read_ms), med(t.parse_ms), med(t.dump_ms),
      med(t.write_ms), mx(t.write_ms), identical ? "byte-identical" : "DIFFERS");
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  std::size_t poses = cosmo::jrl::SyntheticParams{}.poses_per_robot;
  std::string keep;
  cosmo::CommandLine app(
      "bench_jrl_io",
      "Median (and max) over N runs of readJrl (file -> Dataset), parseJrl (text -> Dataset), dumpJrl (Dataset -> "
      "text) and writeJrl (Dataset -> file, atomic, fsync'd), on the reference COSMO-Bench file and a synthetic one.");
  app.add_option("--repeats", repeats, "runs per figure (at least 1)")->capture_default_str();
  app.add_option("--poses", poses, "poses per robot of the synthetic dataset")->capture_default_str();
  app.add_option("--keep", keep, "write the files into DIR and keep them")->type_name("DIR");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  repeats = std::max(1, repeats);
  const fs::path dir =
      keep.empty() ? fs::temp_directory_path() / ("cosmo_bench_jrl_" + std::to_string(::getpid())) : fs::path(keep);
  fs::create_directories(dir);
  std::printf("bench_jrl_io: %d repeats, medians\n", repeats);

  if (const auto ref = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl"))
    measure("tuhh_r3_01_night_wifi.jrl", *ref, repeats, dir.string());
  else
    std::printf("reference file not found (../shared missing): skipped\n");

  std::mt19937_64 rng(42);
  cosmo::jrl::SyntheticParams params;
  params.poses_per_robot = poses;
  Stopwatch sw;
  const auto synth = cosmo::jrl::makeSyntheticDataset(params, rng);
  const double gen_ms = sw.elapsedMs();
  const std::string synth_path = (dir / "synthetic_cosmo.jrl").string();
  cosmo::jrl::writeJrl(synth_path, synth);
  std::size_t factors = 0;
  for (const auto& [r, entries] : synth.measurements)
    for (const auto& e : entries) factors += e.factors.size();
  std::printf("synthetic: %zu robots x %zu poses, %zu factors, generated in %.1f ms\n", synth.robots.size(), poses,
              factors, gen_ms);
  measure("synthetic_cosmo.jrl", synth_path, repeats, dir.string());

  if (keep.empty()) fs::remove_all(dir);
  return 0;
}
