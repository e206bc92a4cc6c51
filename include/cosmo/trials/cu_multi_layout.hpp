#pragma once
// CU-Multi's layout (docs real_data_formats.md §2), for writing trials whose truth is known: one ROS 2 sqlite3
// bag folder per robot `robotN_<trial>_lidar/` (metadata.yaml + `robotN_<trial>_lidar_0.db3`, CDR) with topic
// `robotN/ouster/points` (no leading slash), organised Ouster clouds stamped at the sweep START, 20 Hz; the
// ground truth a CSV with two `#` lines and `timestamp,x,y,z,qx,qy,qz,qw` in UTM (one pose per scan).
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/trials/ouster_cloud.hpp"
#include "cosmo/trials/ros2_bag.hpp"

namespace cosmo::trials {

/// "robotN/ouster/points".
std::string cuMultiTopic(int robot_number);

/// imu_T_lidar as evalio reads it: 180° yaw and (-0.058038, 0.015573, 0.049603).
Pose3 cuMultiImuTLidar();

/// The sweep of a CU-Multi cloud: stamped at its start, ring uint16.
OusterSweep cuMultiSweep(int beams, int columns, double rate_hz);

/// The ground-truth CSV: two `#` lines, then timestamp,x,y,z,qx,qy,qz,qw (seconds, metres as given).
void writeCuMultiGroundTruth(const std::string& path, const std::vector<StampedPose>& body);

/// A robot's LiDAR bag folder: PointCloud2 messages of `cuMultiTopic(robot_number)`, received at their header
/// stamp.
class CuMultiBagWriter {
 public:
  CuMultiBagWriter(const std::string& folder, int robot_number);
  void write(const RawCloud& cloud);
  void close() { bag_.close(); }

 private:
  Ros2BagWriter bag_;
  int topic_;
};

}  // namespace cosmo::trials
