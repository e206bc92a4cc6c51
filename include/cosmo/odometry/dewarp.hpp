#pragma once
// Dewarping (motion correction): every point of a sweep re-expressed in the sensor frame at the scan stamp,
// using a trajectory of sensor poses (the reference trajectory, or odometry in live use).
#include <functional>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"

namespace cosmo::odometry {

/// Returns `scan` with each point p taken at stamp + time[i] mapped to T(stamp)^-1 * T(stamp + time[i]) * p,
/// where T = sensor_pose_at (sensor pose in any fixed frame). Per-point times are zeroed in the result. A scan
/// without times is returned unchanged. `sensor_pose_at` is called at most ~2049 times (times are binned to
/// 1/2048 of the sweep's time span). NaN points stay NaN.
Scan dewarp(const Scan& scan, const std::function<Pose3(StampNs)>& sensor_pose_at);

/// Constant-velocity deskew of feature points: `delta` is the sensor motion over `period` seconds ending at
/// the scan stamp (T(stamp - period)^-1 * T(stamp)); a point at time t (s, relative to the stamp) is mapped to
/// exp((t / period) * log(delta)) * p. `times` empty or `period` <= 0: points copied unchanged.
void deskewConstantVelocity(const std::vector<Eigen::Vector3d>& points, const std::vector<float>& times,
                            const Pose3& delta, double period, std::vector<Eigen::Vector3d>& out);

}  // namespace cosmo::odometry
