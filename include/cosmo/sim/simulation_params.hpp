#pragma once
// Everything that defines a synthetic multi-trial sequence (config/sim/*.yaml): the world, the LiDAR, and
// one entry per trial (robot, platform, route length, motion overrides). The cache key hashes describe().
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/config.hpp"
#include "cosmo/common/pose.hpp"
#include "cosmo/sim/lidar_model.hpp"
#include "cosmo/sim/route_planner.hpp"
#include "cosmo/sim/trajectory_generator.hpp"
#include "cosmo/sim/world_generator.hpp"

namespace cosmo::sim {

/// Bump when a code change alters the generated data (invalidates caches).
inline constexpr const char* kSimCodeVersion = "sim-1";

struct TrialParams {
  std::string robot = "a";       ///< robot id
  std::string name = "trial_a";  ///< trial name: <name>.bag, <name>_pose_inW.csv
  std::string platform = "atv";  ///< handheld | atv | car (motion preset)
  double length = 500.0;         ///< route length along the network, m (when duration <= 0 and no waypoints)
  double duration = 0.0;         ///< s; > 0 sets the route length to about duration * cruise speed
  int start_node = -1;           ///< junction to start from (-1: seeded random)
  RouteParams route;             ///< streets_only, return_fraction, waypoints (start_node is copied in)
  MotionParams motion;
  /// T_body_lidar as x y z qx qy qz qw (LiDAR pose = body pose * extrinsic).
  std::vector<double> extrinsic{0.0, 0.0, 0.25, 0.0, 0.0, 0.0, 1.0};
  Pose3 extrinsicPose() const;
  std::string describe() const;
};

struct SimulationParams {
  std::string name = "synthetic_r3_00";  ///< sequence name (sequence config <name>.yaml)
  std::string source = "synthetic";
  std::string environment = "synthetic";  ///< noise-model environment written into the sequence config
  std::uint64_t seed = 7;                 ///< seeds the world, routes, motion and LiDAR noise
  std::string anchor = "a";
  double time_offset_sigma = 40.0;       ///< s, written into the sequence config (spec section 3)
  double start_epoch = 1.7e9;            ///< s, first stamp of the first trial (realistic UNIX time)
  double trial_epoch_spacing = 86400.0;  ///< s between trial starts (trials recorded on different days)
  std::string topic = "/os_cloud_node/points";
  std::string frame_id = "os_sensor";
  WorldParams world;
  LidarModel lidar;
  std::vector<TrialParams> trials;
  /// `registration:` keys written into the sequence config (config/sequence_format.md): the registration setting
  /// of this sequence's runs on top of config/registration.yaml (scalar values as written; checked when the
  /// sequence config is read). Empty: none written.
  std::map<std::string, std::string> registration;

  /// Parses a config/sim/*.yaml file; errors name the file and key.
  static SimulationParams load(const std::string& path);
  static SimulationParams fromConfig(const ConfigNode& node);
  /// Every parameter (defaults included) and kSimCodeVersion as text.
  std::string describe() const;
  /// 64-bit FNV-1a of describe(), as 16 hex digits.
  std::string hash() const;
};

}  // namespace cosmo::sim
