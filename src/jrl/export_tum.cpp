#include <filesystem>
#include <stdexcept>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/jrl/exports.hpp"
#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::jrl {

namespace {

Trajectory ownTrajectory(const PoseGraph& g, char robot, const PoseMap& poses) {
  std::vector<StampedPose> out;
  for (Key k : g.ownKeys(robot)) {
    const auto pose = poses.find(k);
    const auto stamp = g.stamps.find(k);
    if (pose != poses.end() && stamp != g.stamps.end()) out.push_back({stamp->second, pose->second});
  }
  return Trajectory(std::move(out));
}

}  // namespace

std::vector<std::string> exportTum(const Dataset& dataset, const std::string& dir) {
  const PoseGraph g = poseGraph(dataset);
  std::filesystem::create_directories(dir);
  std::vector<std::string> written;
  for (char r : g.robots) {
    for (const auto& [what, poses] : {std::pair<const char*, const PoseMap*>{"groundtruth", &g.groundtruth},
                                      std::pair<const char*, const PoseMap*>{"initialization", &g.initialization}}) {
      if (poses->empty()) continue;
      const std::string path =
          (std::filesystem::path(dir) / (dataset.name + "_" + std::string(1, r) + "_" + what + ".tum")).string();
      writeTumTrajectory(path, ownTrajectory(g, r, *poses));
      written.push_back(path);
    }
  }
  if (written.empty()) throw std::runtime_error(dataset.name + ": neither ground truth nor initialization to export");
  return written;
}

}  // namespace cosmo::jrl
