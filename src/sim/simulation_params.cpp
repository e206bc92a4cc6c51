#include "cosmo/sim/simulation_params.hpp"

#include <cstdio>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cosmo::sim {

Pose3 TrialParams::extrinsicPose() const {
  if (extrinsic.size() != 7)
    throw std::runtime_error("trial " + name + ": extrinsic needs 7 numbers (x y z qx qy qz qw)");
  return makePose({extrinsic[0], extrinsic[1], extrinsic[2]},
                  Eigen::Quaterniond(extrinsic[6], extrinsic[3], extrinsic[4], extrinsic[5]));
}

std::string TrialParams::describe() const {
  std::ostringstream os;
  os << std::setprecision(17) << "robot=" << robot << ";name=" << name << ";platform=" << platform
     << ";length=" << length << ";duration=" << duration << ";start_node=" << start_node
     << ";streets_only=" << route.streets_only << ";return_fraction=" << route.return_fraction << ";extrinsic=";
  for (double v : extrinsic) os << v << ',';
  if (!route.waypoints.empty()) {  // only when used: the cache keys of configs without waypoints stay valid
    os << ";waypoints=";
    for (int w : route.waypoints) os << w << ',';
  }
  os << ';' << motion.describe();
  return os.str();
}

SimulationParams SimulationParams::load(const std::string& path) { return fromConfig(ConfigNode::load(path)); }

SimulationParams SimulationParams::fromConfig(const ConfigNode& node) {
  SimulationParams p;
  node.read("name", p.name);
  node.read("source", p.source);
  node.read("environment", p.environment);
  node.read("seed", p.seed);
  node.read("anchor", p.anchor);
  node.read("time_offset_sigma", p.time_offset_sigma);
  node.read("start_epoch", p.start_epoch);
  node.read("trial_epoch_spacing", p.trial_epoch_spacing);
  node.read("topic", p.topic);
  node.read("frame_id", p.frame_id);
  p.world = WorldParams::fromConfig(node["world"]);
  p.lidar = LidarModel::fromConfig(node["lidar"]);
  if (node.has("registration")) p.registration = node["registration"].scalarMap("config/registration.yaml keys");
  const ConfigNode trials = node["trials"];
  if (!trials.node || !trials.node.IsSequence() || trials.node.size() == 0)
    throw std::runtime_error(trials.where + ": expected a non-empty list of trials");
  std::set<std::string> robots, names;
  for (std::size_t i = 0; i < trials.node.size(); ++i) {
    ConfigNode t{trials.node[i], trials.where + "[" + std::to_string(i) + "]"};
    TrialParams tp;
    tp.robot = std::string(1, static_cast<char>('a' + i));
    t.read("robot", tp.robot);
    tp.name = p.name + "_" + tp.robot;
    t.read("name", tp.name);
    t.read("platform", tp.platform);
    t.read("length", tp.length);
    t.read("duration", tp.duration);
    t.read("start_node", tp.start_node);
    t.read("extrinsic", tp.extrinsic);
    tp.motion = MotionParams::fromConfig(t["motion"], tp.platform);
    tp.route.streets_only = tp.platform == "car";
    t.read("streets_only", tp.route.streets_only);
    t.read("return_fraction", tp.route.return_fraction);
    t.read("waypoints", tp.route.waypoints);
    if (tp.extrinsic.size() != 7)
      throw std::runtime_error(t.where + ".extrinsic: expected 7 numbers (x y z qx qy qz qw)");
    if (!robots.insert(tp.robot).second) throw std::runtime_error(t.where + ".robot: duplicate robot id " + tp.robot);
    if (!names.insert(tp.name).second) throw std::runtime_error(t.where + ".name: duplicate trial name " + tp.name);
    if (!(tp.length > 0) && !(tp.duration > 0)) throw std::runtime_error(t.where + ": length or duration must be > 0");
    t.rejectUnknownKeys({"robot", "name", "platform", "length", "duration", "start_node", "extrinsic", "motion",
                         "streets_only", "return_fraction", "waypoints"});
    p.trials.push_back(tp);
  }
  if (!robots.count(p.anchor))
    throw std::runtime_error(node.where + "anchor: no trial has robot id '" + p.anchor + "'");
  node.rejectUnknownKeys({"name", "source", "environment", "seed", "anchor", "time_offset_sigma", "start_epoch",
                          "trial_epoch_spacing", "topic", "frame_id", "world", "lidar", "registration", "trials"});
  return p;
}

std::string SimulationParams::describe() const {
  std::ostringstream os;
  os << std::setprecision(17) << "code=" << kSimCodeVersion << "\nname=" << name << ";source=" << source
     << ";environment=" << environment << ";seed=" << seed << ";anchor=" << anchor
     << ";time_offset_sigma=" << time_offset_sigma << ";start_epoch=" << start_epoch
     << ";trial_epoch_spacing=" << trial_epoch_spacing << ";topic=" << topic << ";frame_id=" << frame_id
     << "\nworld:" << world.describe() << "\nlidar:" << lidar.describe();
  for (const auto& t : trials) os << "\ntrial:" << t.describe();
  if (!registration.empty()) {  // only when set: the cache keys of configs without it stay valid
    os << "\nregistration:";
    for (const auto& [key, value] : registration) os << key << '=' << value << ';';
  }
  return os.str();
}

std::string SimulationParams::hash() const {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : describe()) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace cosmo::sim
