#pragma once
// A synthetic LAMP 2.0 team with known truth (for tests and benchmarks): robots on random-walk reference
// trajectories, their incremental pose-graph messages as LAMP publishes them (new nodes and edges per message,
// a full re-publication, the last node repeated after it), edges of every type (ODOM, PRIOR, IMU, LOOPCLOSE,
// ARTIFACT, UWB_RANGE, UWB_BETWEEN, INTERROB_RANGE, INTERROB_BETW) with artifact and UWB-anchor nodes, recorded
// covariances in LAMP's translation-first order, and a known set of wrong loop closures (errors of metres).
// Deterministic in rng.
#include <cstddef>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/nebula/g2o_io.hpp"
#include "cosmo/nebula/pose_graph_msg.hpp"

namespace cosmo::nebula {

struct SyntheticTeamParams {
  std::vector<std::pair<std::string, char>> robots{{"husky3", 'c'}, {"husky4", 'd'}};
  std::size_t poses_per_robot = 80;
  std::size_t poses_per_message = 6;
  double step_m = 2.0;
  double period_s = 2.5;         ///< between a robot's poses (plus up to 0.5 s jitter)
  double start_spacing_s = 7.3;  ///< robot k starts k times this after the first
  StampNs first_stamp = 1'600'000'000'000'000'000ull;
  double lc_probability = 0.12;    ///< per pose, chance of an intra-robot loop closure
  double irlc_probability = 0.12;  ///< per pose, chance of an inter-robot loop closure
  double wrong_ratio = 0.2;        ///< share of loop closures made wrong (1.5-4 m and 0.2-0.5 rad off)
};

struct SyntheticTeam {
  std::map<char, std::string> names;
  std::map<jrl::Key, Pose3> truth;      ///< every robot pose (the reference solution)
  std::map<jrl::Key, Pose3> landmarks;  ///< artifact and UWB-anchor positions (also in result.g2o)
  std::map<char, std::vector<StampNs>> stamps;
  std::map<std::string, std::vector<PoseGraph>> messages;  ///< per robot name, in publication order
  std::map<std::string, std::vector<G2oEdge>> g2o_edges;   ///< per robot name: its odometry and loop closures
  std::set<std::pair<jrl::Key, jrl::Key>> wrong_closures;  ///< (key_from, key_to) as published
  std::size_t intra = 0, inter = 0;
  std::map<std::string, std::size_t> other_edges;        ///< edges of the ignored types written, per type name
  Matrix6 odometry_covariance, loop_closure_covariance;  ///< recorded (rotation first), the noise's true law
};

SyntheticTeam makeSyntheticTeam(const SyntheticTeamParams& params, std::mt19937_64& rng);

}  // namespace cosmo::nebula
