#include "cosmo/ros/nebula_dataset.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "cosmo/nebula/g2o_io.hpp"

namespace cosmo::ros_glue {

namespace fs = std::filesystem;

namespace {

/// Files under `folder` (recursively) ending in `extension`, sorted by path, relative to `root`.
std::vector<std::string> filesUnder(const fs::path& root, const std::string& folder, const std::string& extension) {
  const fs::path dir = root / folder;
  if (!fs::is_directory(dir)) throw std::runtime_error(dir.string() + ": no such folder");
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == extension)
      files.push_back(fs::relative(e.path(), root).string());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw std::runtime_error(dir.string() + ": no " + extension + " file");
  return files;
}

std::map<jrl::Key, Pose3> readReference(const fs::path& root, NebulaConversion& out) {
  const fs::path path = root / "ground_truth" / "result.g2o";
  if (!fs::exists(path)) throw std::runtime_error(path.string() + ": reference solution missing");
  nebula::G2oGraph g = nebula::readG2o(path.string());
  out.inputs.push_back("ground_truth/result.g2o");
  out.reference_poses = g.vertices.size();
  return std::move(g.vertices);
}

}  // namespace

NebulaConversion convertNebulaDataset(const NebulaOptions& options) {
  const fs::path root(options.dataset_dir);
  if (!fs::is_directory(root)) throw std::runtime_error(options.dataset_dir + ": no such dataset folder");
  NebulaConversion out;
  nebula::GraphBuilder builder;
  if (options.from_g2o) {
    for (const std::string& file : filesUnder(root, "g2o_pcd", ".g2o")) {
      builder.addG2o(nebula::readG2o((root / file).string()), file);
      out.inputs.push_back(file);
    }
  } else {
    for (const std::string& file : filesUnder(root, "rosbag", ".bag")) {
      auto topics = readPoseGraphBag((root / file).string(), file, builder, options.covariance_order);
      if (topics.empty()) continue;  // e.g. a bag of other topics only
      out.inputs.push_back(file);
      out.topics.insert(out.topics.end(), topics.begin(), topics.end());
    }
    if (out.topics.empty())
      throw std::runtime_error((root / "rosbag").string() +
                               ": no /<robot>/lamp/pose_graph_incremental topic in any bag");
  }
  const std::map<jrl::Key, Pose3> reference = readReference(root, out);
  out.graph = builder.build();
  if (out.graph.robots.empty()) throw std::runtime_error(options.dataset_dir + ": no robot with odometry edges");
  out.dataset = nebula::assembleJrl(out.graph, reference, options.params, &out.report);
  return out;
}

}  // namespace cosmo::ros_glue
