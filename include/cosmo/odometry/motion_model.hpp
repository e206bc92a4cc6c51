#pragma once
// Constant-velocity motion model: the last scan-to-scan motion, rescaled to the current time step.
#include "cosmo/common/pose.hpp"

namespace cosmo::odometry {

/// The motion expected over `period` seconds given the last motion `last_delta` that took `last_period`
/// seconds (exp((period / last_period) * log(last_delta))). Unknown periods (<= 0): `last_delta` as is.
/// The scale is clamped to [0, 3] so that a long gap in the data does not extrapolate wildly.
Pose3 predictMotion(const Pose3& last_delta, double last_period, double period);

}  // namespace cosmo::odometry
