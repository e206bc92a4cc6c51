#pragma once
// Helpers for tools, benchmarks and tests that evaluate registrations against a known answer: errors of an
// estimate, rotating a scan in yaw, and pair lists with known answers.
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"

namespace cosmo::registration {

struct PoseError {
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};
/// Error of `estimate` against `expected`: |t_e^-1 t| and the angle of R_e^T R.
PoseError poseError(const Pose3& estimate, const Pose3& expected);

/// The scan rotated about the sensor's z axis by `yaw_rad` (points p -> Rz p). If T maps the original source
/// into the target, T * Rz^-1 maps the rotated one.
Scan rotateScanYaw(const Scan& scan, double yaw_rad);

/// A registration problem with a known answer.
struct ScanPair {
  std::string name;
  std::string source;  ///< scan file
  std::string target;  ///< scan file
  Pose3 T_target_source = Pose3::Identity();
  double distance_m = 0.0;  ///< |translation|
};

/// Read a pair list: lines "source target x y z qx qy qz qw" (or 12/16 matrix numbers, or a path to a 4x4
/// file); '#' starts a comment; relative paths are relative to the list's folder.
std::vector<ScanPair> readPairList(const std::string& path);
/// Write the same format (7 numbers).
void writePairList(const std::string& path, const std::vector<ScanPair>& pairs);

}  // namespace cosmo::registration
