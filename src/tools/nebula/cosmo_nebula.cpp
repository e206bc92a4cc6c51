// cosmo_nebula: a Nebula (LAMP 2.0) multi-robot dataset folder as distributed -> a JRL dataset, the way the
// COSMO-Bench paper converts them (§5): per-robot odometry chains, loop closures in the entry of the robot and
// time at which they were made, the prior, groundtruth from ground_truth/result.g2o, dead-reckoned
// initialization, noise models and chi^2 outlier labels.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "cosmo/backend/dataset_check.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/nebula/message_definition.hpp"
#include "cosmo/nebula/metadata.hpp"
#include "cosmo/report/figures.hpp"
#include "cosmo/ros/nebula_dataset.hpp"

namespace {

namespace fs = std::filesystem;

void printSummary(const cosmo::ros_glue::NebulaConversion& c) {
  const auto& g = c.graph;
  std::cout << "read " << c.inputs.size() << " files, " << g.messages << " messages: " << g.nodes_read << " nodes ("
            << g.repeated_nodes << " repeated), " << g.edges_read << " edges (" << g.repeated_edges << " repeated)\n";
  for (const auto& t : c.topics)
    if (!t.md5_matches)
      std::cout << "NOTE: " << t.bag << " " << t.topic << ": md5sum " << t.md5sum << " differs from "
                << cosmo::nebula::kPoseGraphType << "'s " << cosmo::nebula::poseGraphMd5()
                << " (decoded all the same: every message had exactly the expected layout)\n";
  std::cout << "robots:";
  for (const auto& [ch, r] : g.robots)
    std::cout << ' ' << ch << '=' << (r.name.empty() ? "?" : r.name) << " (" << r.stamps.size() << " poses)";
  std::cout << "\nloop closures: " << c.report.intra << " intra, " << c.report.inter << " inter (" << c.report.inverted
            << " stored the other way round: key1 = the later pose)\n";
  std::cout << "ignored edges:";
  if (g.ignored_edges.empty()) std::cout << " none";
  for (const auto& [type, n] : g.ignored_edges) std::cout << ' ' << type << ' ' << n;
  std::cout << "\nother nodes (artifacts, UWB, base):";
  if (g.other_nodes.empty()) std::cout << " none";
  for (const auto& [ch, n] : g.other_nodes) std::cout << ' ' << ch << ' ' << n;
  std::cout << "\n";
  if (g.warnings.total()) std::cout << "WARNINGS (" << g.warnings.total() << "):\n" << g.warnings.str();
  if (c.report.estimate) {
    const auto& e = *c.report.estimate;
    std::cout << "noise models estimated: odometry from " << e.odometry.used << ", loop closures from "
              << e.loop_closure.used << " good ones (" << e.loop_closure.rejected << " over the thresholds)\n";
  }
}

struct Args {
  cosmo::ros_glue::NebulaOptions options;
  std::string out_dir, noise_file, name;
  bool estimate = false;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Args& args) {
  cosmo::ros_glue::NebulaOptions& options = args.options;
  cosmo::CommandLine app(
      "cosmo_nebula",
      "Converts a Nebula dataset folder (rosbag/*.bag with /<robot>/lamp/pose_graph_incremental, "
      "ground_truth/result.g2o) to DIR/<name>.jrl, <name>.stats.txt, <name>.stats.json, <name>.nebula.yaml, the "
      "dataset's figures (<name>.trajectories / .frontend, SVG and PNG) and prints the inliers' solve check.");
  app.add_option("DATASET_DIR", options.dataset_dir, "the Nebula folder as distributed")->required();
  app.add_option("--out", args.out_dir, "output folder")->required()->type_name("DIR");
  app.add_option("--name", args.name, "dataset name (default: the folder's name)");
  CLI::Option* noise = cosmo::addNoiseModels(
      app, args.noise_file,
      "one odometry and one loop-closure covariance for all factors, as config/noise_models/*.yaml; e.g. the one "
      "estimated from tunnel");
  app.add_flag("--estimate-noise-models", args.estimate,
               "estimate them from this dataset against its reference (paper's procedure) and write "
               "DIR/<name>.noise_models.yaml; default: each edge's recorded one")
      ->excludes(noise);
  cosmo::addClosureThresholds(app, "max", options.params.estimation.max_translation_error,
                              options.params.estimation.max_rotation_error);
  app.add_option_function<std::string>(
         "--outlier-rule",
         [&options](const std::string& name) {
           const auto rule = cosmo::dataset::parseOutlierRule(name);
           if (!rule) throw CLI::ValidationError("--outlier-rule", "expected fidelity or squared");
           options.params.rule = *rule;
         },
         "fidelity (sqrt(d2) > 12.592, COSMO-Bench's) | squared (d2 > 12.592)")
      ->type_name("R");
  app.add_option_function<std::string>(
         "--covariance-order",
         [&options](const std::string& order) {
           if (order == "translation-first")
             options.covariance_order = cosmo::nebula::CovarianceOrder::TranslationFirst;
           else if (order == "rotation-first")
             options.covariance_order = cosmo::nebula::CovarianceOrder::RotationFirst;
           else
             throw CLI::ValidationError("--covariance-order",
                                        "expected translation-first or rotation-first, got " + order);
         },
         "recorded covariances' order: translation-first (the message definition's comment; default) | "
         "rotation-first")
      ->type_name("O");
  app.add_flag("--from-g2o", options.from_g2o,
               "read g2o_pcd/*.g2o instead of the bags (no stamps there: pose i of each robot is stamped i seconds; "
               "an edge between consecutive poses of one robot is odometry, any other a loop closure)");
  return app.parseOrExit(argc, argv);
}

/// The dataset's name (default: the folder's) and noise-model source into the conversion's parameters.
void resolveParams(Args& args) {
  auto& params = args.options.params;
  params.name = args.name;
  if (params.name.empty()) {
    fs::path dir = fs::path(args.options.dataset_dir).lexically_normal();
    if (dir.filename().empty()) dir = dir.parent_path();  // "tunnel/" -> "tunnel"
    params.name = dir.filename().string();
  }
  if (params.name.empty() || params.name == "." || params.name == "..")
    throw std::runtime_error("give the dataset a name with --name");
  if (args.estimate) params.noise = cosmo::nebula::NoiseSource::Estimated;
  if (!args.noise_file.empty()) {
    params.noise = cosmo::nebula::NoiseSource::Given;
    params.models = cosmo::dataset::NoiseModels::load(args.noise_file);
  }
}

/// False (with the violations on stderr) when the dataset is not valid JRL.
bool validJrl(const cosmo::jrl::Dataset& dataset) {
  const auto violations = cosmo::jrl::validate(dataset);
  if (violations.empty()) return true;
  std::cerr << "cosmo_nebula: the converted dataset is not valid JRL (" << violations.size()
            << " violations), nothing written:\n";
  for (std::size_t i = 0; i < violations.size() && i < 20; ++i) std::cerr << "  " << violations[i].str() << "\n";
  return false;
}

/// <base>.jrl, .stats.txt, .stats.json, .nebula.yaml, the estimated noise models, then the figures.
void writeOutputs(const Args& args, const cosmo::ros_glue::NebulaConversion& c) {
  const auto& options = args.options;
  const auto& params = options.params;
  fs::create_directories(args.out_dir);
  const fs::path base = fs::path(args.out_dir) / params.name;
  cosmo::jrl::writeJrl(base.string() + ".jrl", c.dataset);
  const cosmo::jrl::DatasetStats stats = cosmo::jrl::computeStats(c.dataset);
  cosmo::dataset::writeFileAtomically(base.string() + ".stats.txt", cosmo::jrl::formatStats(stats) + "\n");
  cosmo::dataset::writeFileAtomically(base.string() + ".stats.json", cosmo::jrl::statsJson(stats) + "\n");
  cosmo::nebula::MetadataInputs inputs{options.dataset_dir, c.inputs, options.from_g2o, options.covariance_order};
  cosmo::dataset::writeFileAtomically(base.string() + ".nebula.yaml",
                                      cosmo::nebula::metadataYaml(c.graph, c.report, params, inputs));
  std::cout << "wrote " << base.string() << ".jrl (+ .stats.txt, .stats.json, .nebula.yaml";
  if (c.report.estimate) {
    std::ostringstream header;
    header << "Noise models estimated by cosmo_nebula from " << options.dataset_dir << ": "
           << c.report.estimate->odometry.used << " odometry factors, " << c.report.estimate->loop_closure.used
           << " good loop closures (error < " << params.estimation.max_translation_error << " m and < "
           << params.estimation.max_rotation_error << " rad)";
    c.report.estimate->models.save(base.string() + ".noise_models.yaml", header.str());
    std::cout << ", .noise_models.yaml";
  }
  std::cout << ")\n" << cosmo::jrl::formatStats(stats) << "\n";
  std::cout << cosmo::backend::inliersSolveLine(c.dataset) << "\n"
            << cosmo::report::writeFiguresBesideJrl(c.dataset, base.string() + ".jrl") << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const std::optional<int> exit_code = parseArgs(argc, argv, args)) return *exit_code;
  try {
    resolveParams(args);
    const cosmo::ros_glue::NebulaConversion c = cosmo::ros_glue::convertNebulaDataset(args.options);
    printSummary(c);
    if (!validJrl(c.dataset)) return 1;
    writeOutputs(args, c);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "cosmo_nebula: " << e.what() << "\n";
    return 1;
  }
}
