// bench_nebula: conversion time of cosmo_nebula on a generated Nebula dataset folder of realistic size (default
// 4 robots x 2,000 poses, LAMP-style incremental messages with edges of every type), by stage.
//   bench_nebula [--robots N] [--poses N] [--repeats N] [--seed S] [--keep DIR]
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <random>
#include <string>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/nebula/g2o_io.hpp"
#include "cosmo/nebula/jrl_assembly.hpp"
#include "cosmo/ros/nebula_dataset.hpp"
#include "cosmo/ros/nebula_synthetic_folder.hpp"
#include "cosmo/ros/pose_graph_bag.hpp"

namespace fs = std::filesystem;
using namespace cosmo;

int main(int argc, char** argv) {
  std::size_t robots = 4, poses = 2000, repeats = 3;
  std::uint64_t seed = 1;
  std::string keep;
  cosmo::CommandLine app("bench_nebula",
                         "Conversion time of cosmo_nebula on a generated Nebula dataset folder of realistic size "
                         "(LAMP-style incremental messages with edges of every type), by stage.");
  app.add_option("--robots", robots, "robots (1-4)")->capture_default_str();
  app.add_option("--poses", poses, "poses per robot")->capture_default_str();
  app.add_option("--repeats", repeats, "conversions timed")->capture_default_str();
  app.add_option("--seed", seed, "the generator's seed")->capture_default_str();
  app.add_option("--keep", keep, "write the folder into DIR and keep it")->type_name("DIR");
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  const std::vector<std::pair<std::string, char>> all{
      {"husky1", 'a'}, {"husky2", 'b'}, {"husky3", 'c'}, {"husky4", 'd'}};
  nebula::SyntheticTeamParams params;
  params.robots.assign(all.begin(),
                       all.begin() + static_cast<long>(std::min<std::size_t>(std::max<std::size_t>(robots, 1), 4)));
  params.poses_per_robot = poses;
  std::mt19937_64 rng(seed);
  bench::Stopwatch sw;
  const nebula::SyntheticTeam team = makeSyntheticTeam(params, rng);
  const fs::path dir =
      keep.empty() ? fs::temp_directory_path() / ("cosmo_bench_nebula_" + std::to_string(::getpid())) : fs::path(keep);
  fs::remove_all(dir);
  ros_glue::writeNebulaFolder(dir.string(), team);
  std::uintmax_t bag_bytes = 0;
  std::size_t messages = 0;
  for (const auto& e : fs::directory_iterator(dir / "rosbag")) bag_bytes += fs::file_size(e.path());
  for (const auto& [name, list] : team.messages) messages += list.size();
  std::cout << "fixture: " << params.robots.size() << " robots x " << poses << " poses, " << messages
            << " messages, bags " << std::fixed << std::setprecision(1) << bag_bytes / 1e6 << " MB, " << team.intra
            << " + " << team.inter << " loop closures (" << team.wrong_closures.size()
            << " wrong); generated and written in " << std::setprecision(0) << sw.elapsedMs() << " ms\n";

  std::vector<double> read_ms, build_ms, recorded_ms, estimated_ms, validate_ms, write_ms, total_ms;
  std::size_t jrl_bytes = 0;
  for (std::size_t r = 0; r < repeats; ++r) {
    // Stages, as convertNebulaDataset runs them.
    sw.restart();
    nebula::GraphBuilder builder;
    for (const auto& e : fs::directory_iterator(dir / "rosbag"))
      ros_glue::readPoseGraphBag(e.path().string(), e.path().filename().string(), builder);
    const auto reference = nebula::readG2o((dir / "ground_truth" / "result.g2o").string()).vertices;
    read_ms.push_back(sw.elapsedMs());
    sw.restart();
    const nebula::NebulaGraph graph = builder.build();
    build_ms.push_back(sw.elapsedMs());
    nebula::ConversionParams p;
    sw.restart();
    const jrl::Dataset ds = nebula::assembleJrl(graph, reference, p);
    recorded_ms.push_back(sw.elapsedMs());
    p.noise = nebula::NoiseSource::Estimated;
    sw.restart();
    const jrl::Dataset est = nebula::assembleJrl(graph, reference, p);
    estimated_ms.push_back(sw.elapsedMs());
    sw.restart();
    if (!jrl::validate(est).empty()) {
      std::cerr << "bench_nebula: converted dataset does not validate\n";
      return 1;
    }
    validate_ms.push_back(sw.elapsedMs());
    sw.restart();
    jrl::writeJrl((dir / "bench.jrl").string(), est);
    write_ms.push_back(sw.elapsedMs());
    jrl_bytes = fs::file_size(dir / "bench.jrl");
    // End to end (read, merge, assemble with estimated models).
    sw.restart();
    ros_glue::NebulaOptions o;
    o.dataset_dir = dir.string();
    o.params.noise = nebula::NoiseSource::Estimated;
    ros_glue::convertNebulaDataset(o);
    total_ms.push_back(sw.elapsedMs());
  }
  auto row = [](const char* what, const std::vector<double>& v) {
    std::cout << "  " << std::left << std::setw(44) << what << std::right << std::setw(8) << std::setprecision(0)
              << bench::quantile(v, 0.5) << " ms  (min " << *std::min_element(v.begin(), v.end()) << ")\n";
  };
  std::cout << "median of " << repeats << " runs (wall clock):\n";
  row("read bags + decode + result.g2o", read_ms);
  row("merge into the team graph", build_ms);
  row("JRL assembly, recorded covariances", recorded_ms);
  row("JRL assembly, estimated models + labels", estimated_ms);
  row("validate", validate_ms);
  row("write JRL", write_ms);
  row("end to end (convertNebulaDataset, estimated)", total_ms);
  std::cout << "  JRL " << std::setprecision(1) << jrl_bytes / 1e6 << " MB\n";
  if (keep.empty()) fs::remove_all(dir);
  return 0;
}
