#pragma once
// The Multi-Campus Dataset's layout (docs real_data_formats.md §1), for writing trials whose truth is known:
// `<seq>/<seq>_os1_<beams>.bag` (ROS 1, bz2 chunks; src/ros/trial_layout_writer.cpp), topic
// /os_cloud_node/points, organised Ouster clouds stamped at the sweep end with `ring` uint8; `<seq>/pose_inW.csv`
// (header num,t,x,y,z,qx,qy,qz,qw: the BODY pose, row `num` N at the stamp of cloud N-1); calibration.yaml
// with `body: os_sensor: T` = T_body_lidar.
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/trials/ouster_cloud.hpp"

namespace cosmo::trials {

inline constexpr const char* kMcdTopic = "/os_cloud_node/points";

/// T_body_lidar of MCD's handheld rig (KTH, TUHH) and of its ATV (NTU), from the dataset's calibration.
Pose3 mcdHandheldExtrinsic();
Pose3 mcdAtvExtrinsic();

/// The sweep of an MCD cloud: stamped at its end, ring uint8.
OusterSweep mcdSweep(int beams, int columns, double rate_hz);

/// pose_inW.csv: one row per stamp, `num` = first_num, first_num + 1, ...; body poses in the world.
void writeMcdPoseCsv(const std::string& path, const std::vector<StampedPose>& body, int first_num);

/// calibration.yaml: `body: os_sensor: T:` as four rows of four numbers.
void writeMcdCalibration(const std::string& path, const Pose3& T_body_lidar);

}  // namespace cosmo::trials
