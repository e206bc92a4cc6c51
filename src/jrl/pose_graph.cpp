#include "cosmo/jrl/pose_graph.hpp"

#include <set>
#include <stdexcept>

namespace cosmo::jrl {

const char* factorKindName(FactorKind kind) {
  switch (kind) {
    case FactorKind::Prior: return "prior";
    case FactorKind::Odometry: return "odometry";
    case FactorKind::LoopClosure: return "lc";
    case FactorKind::InterRobotLoopClosure: return "irlc";
  }
  return "?";
}

namespace {

FactorKind kindOf(Key key1, Key key2) {
  if (robotOf(key1) != robotOf(key2)) return FactorKind::InterRobotLoopClosure;
  return indexOf(key2) == indexOf(key1) + 1 ? FactorKind::Odometry : FactorKind::LoopClosure;
}

const std::set<FactorId>* idsOf(const std::optional<std::map<char, std::set<FactorId>>>& lists, char robot) {
  if (!lists) return nullptr;
  const auto it = lists->find(robot);
  return it == lists->end() ? nullptr : &it->second;
}

PoseFactor makeFactor(const Dataset& d, char robot, std::size_t e, std::size_t m) {
  const Entry& entry = d.measurements.at(robot)[e];
  const Factor& f = entry.factors[m];
  if (!f.isPriorPose3() && !f.isBetweenPose3())
    throw std::runtime_error(d.name + ": measurements." + std::string(1, robot) + "[" + std::to_string(e) +
                             "].measurements[" + std::to_string(m) + "]: " + factorTag(f.type) +
                             " is not a Pose3 prior or between factor");
  PoseFactor p;
  p.robot = robot;
  p.id = FactorId{e, m};
  p.stamp = entry.stamp;
  p.key1 = f.keys.front();
  p.key2 = f.keys.back();
  p.kind = f.isPriorPose3() ? FactorKind::Prior : kindOf(p.key1, p.key2);
  p.measured = f.pose3();
  p.covariance = f.covarianceMatrix();
  const auto* potential = idsOf(d.potential_outliers, robot);
  const auto* outliers = idsOf(d.outliers, robot);
  p.potential_outlier = potential && potential->count(p.id);
  p.outlier = outliers && outliers->count(p.id);
  return p;
}

}  // namespace

std::vector<Key> PoseGraph::ownKeys(char robot) const {
  std::vector<Key> keys;
  const PoseMap& values = groundtruth.empty() ? initialization : groundtruth;
  for (auto it = values.lower_bound(symbol(robot, 0)); it != values.end() && robotOf(it->first) == robot; ++it)
    keys.push_back(it->first);
  return keys;
}

PoseMap ownerPoses(const std::vector<char>& robots, const std::map<char, Values>& values) {
  PoseMap poses;
  for (int pass = 0; pass < 2; ++pass) {  // owners first, then any other holder
    for (char r : robots) {
      const auto it = values.find(r);
      if (it == values.end()) continue;
      for (const auto& [key, value] : it->second) {
        const auto* p = std::get_if<Pose3Value>(&value);
        if (!p || (pass == 0) != (robotOf(key) == r)) continue;
        poses.emplace(key, p->toPose());  // keeps the first value inserted
      }
    }
  }
  return poses;
}

PoseGraph poseGraph(const Dataset& d) {
  PoseGraph g;
  g.name = d.name;
  g.robots = d.robots;
  g.has_outlier_labels = d.outliers.has_value();
  for (char r : d.robots) {
    const auto it = d.measurements.find(r);
    if (it == d.measurements.end()) continue;
    for (std::size_t e = 0; e < it->second.size(); ++e)
      for (std::size_t m = 0; m < it->second[e].factors.size(); ++m) {
        g.factors.push_back(makeFactor(d, r, e, m));
        const PoseFactor& f = g.factors.back();
        for (Key k : {f.key1, f.key2})
          if (robotOf(k) == r) g.stamps.emplace(k, f.stamp);
      }
  }
  if (d.initialization) g.initialization = ownerPoses(d.robots, *d.initialization);
  if (d.groundtruth) g.groundtruth = ownerPoses(d.robots, *d.groundtruth);
  return g;
}

}  // namespace cosmo::jrl
