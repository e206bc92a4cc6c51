#include "cosmo/sim/sequence_planner.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <random>
#include <stdexcept>

#include "cosmo/sim/route_planner.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/sim/trajectory_generator.hpp"
#include "cosmo/sim/world_generator.hpp"

namespace cosmo::sim {

std::uint64_t deriveSeed(std::uint64_t seed, const std::string& label) {
  std::uint64_t h = 0xcbf29ce484222325ULL ^ seed;
  for (unsigned char c : label) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return splitmix64(h);
}

PlannedSequence planSequence(const SimulationParams& params) {
  PlannedSequence seq;
  const WorldLayout layout = generateLayout(params.world, deriveSeed(params.seed, "world"));
  seq.world = std::make_shared<const World>(layoutWorld(layout));
  const World& world = *seq.world;
  const bool per_trial = changesPerTrial(params.world);
  const double period = params.lidar.period();
  for (std::size_t i = 0; i < params.trials.size(); ++i) {
    PlannedTrial t;
    t.params = params.trials[i];
    std::mt19937_64 rng(deriveSeed(params.seed, "trial/" + t.params.name));
    RouteParams rp = t.params.route;
    rp.start_node = t.params.start_node;
    rp.length = t.params.duration > 0 ? t.params.duration * t.params.motion.cruise_speed * 0.9 : t.params.length;
    t.route = planRoute(world.network(), rp, rng);
    std::vector<Eigen::Vector2d> pts;
    for (int n : t.route) pts.push_back(world.network().nodes[n]);
    if (pts.size() < 2) throw std::runtime_error("trial " + t.params.name + ": route has fewer than two junctions");
    const StampNs start = toStampNs(params.start_epoch + static_cast<double>(i) * params.trial_epoch_spacing);
    t.body = makeTrajectory(pts, world.terrain(), t.params.motion, start, rng);
    // Sweeps end every period after the first full sweep; the last one ends inside the trajectory.
    const auto period_ns = static_cast<StampNs>(std::llround(period * 1e9));
    for (StampNs s = t.body.startStamp() + period_ns; s <= t.body.endStamp(); s += period_ns)
      t.scan_stamps.push_back(s);
    t.noise_seed = deriveSeed(params.seed, "lidar/" + t.params.name);
    t.world = per_trial
                  ? std::make_shared<const World>(layoutWorld(layout, deriveSeed(params.seed, "day/" + t.params.name)))
                  : seq.world;
    seq.trials.push_back(std::move(t));
  }
  return seq;
}

void writeSequenceConfig(const std::string& path, const SimulationParams& params) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write sequence config");
  out << std::setprecision(12);
  out << "# Synthetic sequence written by cosmo_simulate (code " << kSimCodeVersion << ", parameter hash "
      << params.hash() << ")\n";
  out << "name: " << params.name << "\n";
  out << "source: " << params.source << "\n";
  out << "environment: " << params.environment << "  # noise models: config/noise_models/" << params.environment
      << ".yaml\n";
  out << "seed: " << params.seed << "\n";
  out << "anchor: " << params.anchor << "\n";
  out << "time_offset_sigma: " << params.time_offset_sigma << "\n";
  out << "trials:\n";
  for (const auto& t : params.trials) {
    out << "  - robot: " << t.robot << "\n";
    out << "    name: " << t.name << "\n";
    out << "    bag: " << t.name << ".bag\n";
    out << "    topic: " << params.topic << "\n";
    out << "    reference: " << t.name << "_pose_inW.csv\n";
    out << "    extrinsic: [";
    for (std::size_t k = 0; k < t.extrinsic.size(); ++k) out << (k ? ", " : "") << t.extrinsic[k];
    out << "]\n";
  }
  if (!params.registration.empty()) {
    out << "registration:  # this sequence's registration keys, on top of config/registration.yaml\n";
    for (const auto& [key, value] : params.registration) out << "  " << key << ": " << value << "\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace cosmo::sim
