#pragma once
// Trajectory files: KITTI (12 numbers per line, row-major 3x4), TUM (t x y z qx qy qz qw), MCD pose_inW.csv
// (num, sec, x, y, z, qx, qy, qz, qw; a header line is allowed) and KITTI calib (Tr: velodyne -> cam0).
// Errors throw std::runtime_error naming the file and line.
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/trajectory.hpp"

namespace cosmo {

std::vector<Pose3> readKittiPoses(const std::string& path);
void writeKittiPoses(const std::string& path, const std::vector<Pose3>& poses);
void writeTumTrajectory(const std::string& path, const Trajectory& trajectory);
Trajectory readTumTrajectory(const std::string& path);
/// MCD-style CSV: num, sec, x, y, z, qx, qy, qz, qw (sec may be fractional seconds since the epoch).
Trajectory readMcdPoseCsv(const std::string& path);
void writeMcdPoseCsv(const std::string& path, const Trajectory& trajectory);
/// The `Tr:` line of a KITTI calib.txt as a 4x4 pose (velodyne -> cam0).
Pose3 readKittiCalibTr(const std::string& path);
/// KITTI ground truth (cam0 frame) expressed as LiDAR poses relative to the first LiDAR frame:
/// T_velo(i) = Tr^-1 * P(i) * Tr.
std::vector<Pose3> kittiPosesToLidar(const std::vector<Pose3>& cam_poses, const Pose3& Tr);
/// A pose line "x y z qx qy qz qw" (7 numbers) or a 3x4 / 4x4 matrix (12 / 16 numbers), row-major.
Pose3 parsePoseNumbers(const std::vector<double>& v, const std::string& where);
/// Read a single pose from a text file holding a 4x4 matrix (e.g. relative.txt).
Pose3 readMatrixPose(const std::string& path);

}  // namespace cosmo
