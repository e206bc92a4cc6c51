#pragma once
// A sequence config (config/sequences/*.yaml, format in config/sequence_format.md): a named set of trials, one
// per robot, with the anchor robot and the seed of every random choice. The trials' data files (bag,
// reference) are relative to the data root, the other paths (noise_models) to the config file's folder.
// Errors throw std::runtime_error naming the file and the field.
//
// Data root, first one set wins: the caller's argument (cosmo_generate / cosmo_check --data-root, the launch's
// data_root:=), the file's `data_root:` key (relative to the file's folder), the COSMO_DATA_ROOT environment
// variable, the config file's folder.
//
// `registration:` (optional) sets keys of config/registration.yaml for this sequence's runs only, on top of the
// config folder's file: a dataset made with a registration setting of its own (the demo: the paper's
// KISS-Matcher alone, `refine: false`, `gate: paper`) says so in its own config, and every driver that runs it
// uses the same setting.
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/registration/registration_params.hpp"

namespace cosmo::sequence {

/// One robot's recording.
struct TrialConfig {
  char robot = 'a';                             ///< robot id (a, b, c, ...)
  std::string name;                             ///< trial name (MCD: ntu_day_01, ...)
  std::string bag;                              ///< absolute path of the bag
  std::string topic = "/os_cloud_node/points";  ///< PointCloud2 topic in the bag
  std::string reference;                        ///< absolute path of the reference CSV; empty: none
  Pose3 extrinsic = Pose3::Identity();          ///< T_body_lidar (LiDAR pose = body pose * extrinsic)
  bool stamp_at_end = true;                     ///< `stamp: end` (Ouster/MCD) or `stamp: start` (CU-Multi)
};

/// How the references' world frame is moved near the origin (one offset for the whole sequence: trials that
/// share a frame, e.g. CU-Multi's UTM, keep sharing it).
struct ReferenceOffsetConfig {
  enum class Mode { None, Anchor, Fixed };
  Mode mode = Mode::None;  ///< `none`, `anchor` (the anchor's first reference position, whole metres)
  Eigen::Vector3d fixed = Eigen::Vector3d::Zero();  ///< `[x, y, z]`
};

struct SequenceConfig {
  std::string path;                 ///< the file it was read from ("" when built in code)
  std::string name = "sequence";    ///< dataset name; the JRL is <name>_<comm>.jrl
  std::string source = "unknown";   ///< metadata (synthetic, MCD, CU-Multi)
  unsigned long long seed = 0;      ///< seeds every random choice
  char anchor = 'a';                ///< robot whose trial starts at t*
  double time_offset_sigma = 40.0;  ///< s, sigma of the N(0, sigma) start offsets of the other trials
  std::string environment;          ///< noise-model environment (config/noise_models/<environment>.yaml); "": none
  std::string noise_models;         ///< absolute path of a noise-model YAML; empty: by environment
  ReferenceOffsetConfig reference_offset;  ///< subtracted from every reference position
  std::string data_root;                   ///< the folder the trials' relative paths were resolved against
  std::string data_root_from;  ///< where it came from: argument, data_root key, COSMO_DATA_ROOT, config folder
  std::vector<TrialConfig> trials;
  /// `registration:` keys of this sequence (config/registration.yaml keys, scalar values as written); checked by
  /// load() against RegistrationParams (an unknown key or a bad value names the file and the key).
  std::map<std::string, std::string> registration;

  /// Read and check a sequence config. `data_root`: the caller's data root (empty: the precedence above).
  static SequenceConfig load(const std::string& path, const std::string& data_root = "");

  std::vector<char> robots() const;
  const TrialConfig& trial(char robot) const;  ///< throws naming the file when the robot is unknown

  /// The registration parameters of this sequence's runs: `<config_dir>/registration.yaml` (the compiled-in
  /// defaults when the file is absent) with this sequence's `registration:` keys on top.
  registration::RegistrationParams registrationParams(const std::string& config_dir) const;
};

/// `<config_dir>/registration.yaml` (the compiled-in defaults when the file is absent) with `keys` (config/
/// registration.yaml keys, values as written) on top; `from` names where the keys come from in error messages.
registration::RegistrationParams registrationParamsWith(const std::string& config_dir,
                                                        const std::map<std::string, std::string>& keys,
                                                        const std::string& from);

/// `path` when absolute, else `base_dir/path` (an empty path stays empty).
std::string resolvePath(const std::string& base_dir, const std::string& path);

}  // namespace cosmo::sequence
