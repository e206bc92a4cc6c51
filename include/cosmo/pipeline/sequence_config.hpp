#pragma once
// A sequence config (config/sequences/*.yaml, format in config/sequence_format.md): a named set of trials, one
// per robot, with the anchor robot and the seed of every random choice. Relative paths are resolved against
// the config file's folder. Errors throw std::runtime_error naming the file and the field.
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"

namespace cosmo::pipeline {

/// One robot's recording.
struct TrialConfig {
  char robot = 'a';                          ///< robot id (a, b, c, ...)
  std::string name;                          ///< trial name (MCD: ntu_day_01, ...)
  std::string bag;                           ///< absolute path of the bag
  std::string topic = "/os_cloud_node/points";  ///< PointCloud2 topic in the bag
  std::string reference;                     ///< absolute path of the reference CSV; empty: none
  Pose3 extrinsic = Pose3::Identity();       ///< T_body_lidar (LiDAR pose = body pose * extrinsic)
  bool stamp_at_end = true;                  ///< scans stamped at sweep end (Ouster/MCD convention)
};

struct SequenceConfig {
  std::string path;                    ///< the file it was read from ("" when built in code)
  std::string name = "sequence";       ///< dataset name; the JRL is <name>_<comm>.jrl
  std::string source = "unknown";      ///< metadata (synthetic, MCD, CU-Multi)
  unsigned long long seed = 0;         ///< seeds every random choice
  char anchor = 'a';                   ///< robot whose trial starts at t*
  double time_offset_sigma = 40.0;     ///< s, sigma of the N(0, sigma) start offsets of the other trials
  std::string environment;             ///< noise-model environment (config/noise_models/<environment>.yaml); "": none
  std::string noise_models;            ///< absolute path of a noise-model YAML; empty: by environment
  std::vector<TrialConfig> trials;

  /// Read and check a sequence config; relative paths resolve against the file's folder.
  static SequenceConfig load(const std::string& path);

  std::vector<char> robots() const;
  const TrialConfig& trial(char robot) const;  ///< throws naming the file when the robot is unknown
};

/// `path` when absolute, else `base_dir/path` (an empty path stays empty).
std::string resolvePath(const std::string& base_dir, const std::string& path);

}  // namespace cosmo::pipeline
