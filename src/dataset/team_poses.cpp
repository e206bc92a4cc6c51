#include "cosmo/dataset/team_poses.hpp"

#include <set>

namespace cosmo::dataset {

std::vector<const jrl::PoseFactor*> TeamPoses::closures(bool inter) const {
  std::vector<const jrl::PoseFactor*> out;
  for (const jrl::PoseFactor& f : loop_closures)
    if ((f.kind == jrl::FactorKind::InterRobotLoopClosure) == inter) out.push_back(&f);
  return out;
}

std::size_t TeamPoses::poseCount() const {
  std::size_t n = 0;
  for (const auto& [robot, poses] : robots) n += poses.size();
  return n;
}

TeamPoses teamPoses(const jrl::PoseGraph& graph) {
  TeamPoses team;
  std::map<jrl::Key, std::pair<std::size_t, StampNs>> made;  // own key -> first entry of its owner referring to it
  for (const jrl::PoseFactor& f : graph.factors) {
    for (jrl::Key k : {f.key1, f.key2})
      if (jrl::robotOf(k) == f.robot) made.emplace(k, std::make_pair(f.id.entry, f.stamp));
    if (f.isLoopClosure()) team.loop_closures.push_back(f);
  }
  for (const auto& [key, where] : made) {  // key order = robot, then index
    const auto truth = graph.groundtruth.find(key);
    if (truth == graph.groundtruth.end()) continue;
    team.robots[jrl::robotOf(key)].push_back(TeamPose{key, where.first, where.second, truth->second});
  }
  return team;
}

}  // namespace cosmo::dataset
