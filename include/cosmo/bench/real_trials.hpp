#pragma once
// The trial list the real-data benchmarks read (bench_scancontext_sim, bench_registration_sim): a YAML file with
// `trials:`, each a ROS 1 bag, an MCD-style reference CSV (body poses), an optional body->LiDAR extrinsic
// (x y z qx qy qz qw) and topic; relative paths are relative to the file. Each trial's scans come dewarped with the
// reference trajectory.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/odometry/dewarp.hpp"

namespace cosmo::bench {

struct RealTrial {
  std::string robot;  ///< the `robot` key, empty where absent
  std::filesystem::path bag, reference;
  std::string topic;
  Pose3 T_body_lidar;
  /// The reference body trajectory (read by readRealTrials only where both files exist).
  Trajectory body;
  bool present = false;  ///< both the bag and the reference exist

  /// Points moved to the sensor frame at the scan stamp with the reference LiDAR trajectory.
  Scan dewarped(const Scan& scan) const {
    return odometry::dewarp(scan, [&](StampNs t) { return body.atClamped(t) * T_body_lidar; });
  }
  Pose3 lidarPoseAt(StampNs t) const { return body.atClamped(t) * T_body_lidar; }
};

inline std::vector<RealTrial> readRealTrials(const std::string& yaml_path) {
  namespace fs = std::filesystem;
  const YAML::Node root = YAML::LoadFile(yaml_path);
  const fs::path dir = fs::path(yaml_path).parent_path();
  auto resolve = [&](const std::string& f) { return fs::path(f).is_absolute() ? fs::path(f) : dir / f; };
  std::vector<RealTrial> out;
  for (const auto& t : root["trials"]) {
    RealTrial trial;
    if (t["robot"]) trial.robot = t["robot"].as<std::string>();
    trial.bag = resolve(t["bag"].as<std::string>());
    trial.reference = resolve(t["reference"].as<std::string>());
    const std::vector<double> e =
        t["extrinsic"] ? t["extrinsic"].as<std::vector<double>>() : std::vector<double>{0, 0, 0, 0, 0, 0, 1};
    trial.T_body_lidar = parsePoseNumbers(e, yaml_path + ": extrinsic");
    trial.topic = t["topic"] ? t["topic"].as<std::string>() : "/os_cloud_node/points";
    trial.present = fs::exists(trial.bag) && fs::exists(trial.reference);
    if (trial.present) trial.body = readMcdPoseCsv(trial.reference.string());
    out.push_back(std::move(trial));
  }
  return out;
}

}  // namespace cosmo::bench
