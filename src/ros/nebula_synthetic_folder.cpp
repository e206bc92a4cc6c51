#include "cosmo/ros/nebula_synthetic_folder.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cosmo/nebula/g2o_io.hpp"
#include "cosmo/ros/pose_graph_bag.hpp"

namespace cosmo::ros_glue {

namespace fs = std::filesystem;

namespace {

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace

void writeNebulaFolder(const std::string& dir, const nebula::SyntheticTeam& team) {
  const fs::path root(dir);
  for (const char* sub : {"rosbag", "g2o_pcd", "ground_truth"}) fs::create_directories(root / sub);
  for (const auto& [c, name] : team.names) {
    PoseGraphBagWriter bag((root / "rosbag" / (name + ".bag")).string());
    for (const nebula::PoseGraph& msg : team.messages.at(name))
      bag.write("/" + name + "/lamp/pose_graph_incremental", msg);
    bag.close();
    std::map<std::uint64_t, Pose3> own;
    for (auto it = team.truth.lower_bound(jrl::symbol(c, 0)); it != team.truth.end() && jrl::robotOf(it->first) == c;
         ++it)
      own.insert(*it);
    writeText(root / "g2o_pcd" / (name + ".g2o"), nebula::g2oText(own, team.g2o_edges.at(name)));
  }
  std::map<std::uint64_t, Pose3> reference(team.truth.begin(), team.truth.end());
  reference.insert(team.landmarks.begin(), team.landmarks.end());
  writeText(root / "ground_truth" / "result.g2o", nebula::g2oText(reference));
}

}  // namespace cosmo::ros_glue
