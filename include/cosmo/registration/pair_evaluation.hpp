#pragma once
// Helpers for tools, benchmarks and tests that evaluate registrations against a known answer: errors of an
// estimate, rotating a scan in yaw, and the known relative poses of the real snippets in ../shared.
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"

namespace cosmo {

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
  std::string source;        ///< scan file
  std::string target;        ///< scan file
  Pose3 T_target_source = Pose3::Identity();
  double distance_m = 0.0;   ///< |translation|
};

/// The real pairs of ../shared/data/scan_snippets named in issue 6 (KITTI 00 0-1, 0-2, 94-95, 198-199, 0-20,
/// 20-40, the hdl32 pair, consecutive MulRan KAIST03 keyframes 0..20 when `all_mulran`, else 0-1 and 5-6),
/// for the snippets folder `root`. Missing files throw naming the file.
std::vector<ScanPair> snippetPairs(const std::string& root, bool all_mulran = true);

/// Read a pair list: lines "source target x y z qx qy qz qw" (or 12/16 matrix numbers, or a path to a 4x4
/// file); '#' starts a comment; relative paths are relative to the list's folder.
std::vector<ScanPair> readPairList(const std::string& path);
/// Write the same format (7 numbers).
void writePairList(const std::string& path, const std::vector<ScanPair>& pairs);

}  // namespace cosmo
