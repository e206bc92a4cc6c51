#pragma once
// Refinement of a registered scan with a continuous-time rotation: the sensor's rotation over the sweep is
// estimated together with its pose, instead of being taken from a prediction. The rotation at the sweep's start
// is a third unknown next to the stamp's rotation and translation; a feature at fraction s of the sweep is
// deskewed with the rotation interpolated between the two (its translation still comes from the prediction), so
// a walker's roll / pitch sway, which changes within a sweep and is not predicted by the previous scan's motion,
// is followed. The start rotation is tied to the previous scan's pose by a soft prior: tied rigidly, the
// deskew errors feed back through the local map as a period-2 oscillation (four of six simulated vehicle trials
// oscillated); left free, a deformation shared with the map's scans is not observable (it drifted).
#include "cosmo/odometry/feature_registration.hpp"

namespace cosmo::odometry {

/// Gauss-Newton on `previous`' constraints (its map lines / planes; no new association) for the scan's pose
/// (update about the sensor position, as robustGaussNewtonStep) and the rotation at the sweep's start, which is
/// pulled towards `previous_pose`'s rotation with weight `tie` x the constraints' rotational information (trace
/// / 3 of the rigid rotation block). The features are re-deskewed at every step: rotation interpolated from the
/// start rotation to the pose's (fraction s = 1 + t / period of a point at time t <= 0 before the stamp),
/// translation from `predicted_delta` (the motion over `period` the registration was deskewed with). At most
/// `max_steps` steps; directions with too little information keep their value (solution remapping). Sets the
/// result's sweep_rotation; `previous` is returned unchanged when it has no constraints.
FeatureRegistrationResult refineContinuousRotation(const LoamFeatures& features, FeatureRegistrationResult previous,
                                                   const LoamParams& params, const Pose3& previous_pose,
                                                   const Pose3& predicted_delta, double period, double tie,
                                                   int max_steps);

}  // namespace cosmo::odometry
