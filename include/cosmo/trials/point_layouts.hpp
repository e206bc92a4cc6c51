#pragma once
// The point layouts of the LiDARs robots carry, written from a simulated scan so that the truth is known
// (cosmo_simulate --points; docs/data.md tables their per-point time and ring). A simulated scan is stamped at its
// sweep end, its points' times <= 0 relative to that stamp, ring = beam; every layout here keeps that header stamp
// and writes one row of the scan's points:
//  - ouster: x y z intensity float32, `t` uint32 ns from the sweep's first point, `ring` uint16 (point_step 22;
//    ros_glue::toPointCloud2 writes it, what cosmo's own bags have always held);
//  - velodyne (velodyne_pointcloud's PointXYZIRT): x y z @0/4/8, intensity float32 @16, `ring` uint16 @20, `time`
//    float32 s from the sweep's first point @24, point_step 32;
//  - hesai (Hesai's PointXYZIT): x y z @0/4/8, intensity float32 @16, `timestamp` float64 absolute s @24, `ring`
//    uint16 @32, point_step 48;
//  - livox (livox_ros_driver2's PointCloud2): x y z intensity float32 @0/4/8/12, `tag` uint8 @16, `line` uint8 @17,
//    `timestamp` float64 absolute ns @18, point_step 26;
//  - livox-custom: livox_ros_driver/CustomMsg (serializeLivoxCustomMsg, ros1_point_cloud.hpp);
//  - split-time (an automotive LiDAR's): x y z @0/4/8, intensity float32 @16, `time_sec` uint32 @20, `time_nsec`
//    uint32 @24, `laser_id` uint16 @28, point_step 32.
#include <optional>
#include <string>

#include "cosmo/common/scan.hpp"
#include "cosmo/trials/point_cloud_decode.hpp"

namespace cosmo::trials {

enum class PointLayout { Ouster, Velodyne, Hesai, Livox, LivoxCustom, SplitTime };

/// "ouster", "velodyne", "hesai", "livox", "livox-custom", "split-time".
std::string pointLayoutName(PointLayout layout);
/// The names joined by '|' (for a command line's help).
std::string pointLayoutNames();
std::optional<PointLayout> parsePointLayout(const std::string& name);

/// The scan as a PointCloud2 of `layout` (velodyne, hesai, livox or split-time; std::invalid_argument for the
/// others, which are written elsewhere, see above). The scan needs per-point times.
RawCloud pointLayoutCloud(const Scan& scan, PointLayout layout, const std::string& frame_id);

}  // namespace cosmo::trials
