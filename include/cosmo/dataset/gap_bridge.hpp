#pragma once
// The odometry factor across a front-end's restart (real time): the restarted front-end has lost its odometry, so
// its first keyframe is joined to the robot's last recorded keyframe by this rule, to keep one connected trajectory
// per robot. Every bridge is listed in the dataset's <name>.recorder.yaml (robot, keys, gap, rule), so that a
// back-end can drop or down-weight it.
// - rule "reference" (both keyframes have a reference pose): the measurement is the relative reference pose
//   T_before^-1 * T_after, with the covariance odometry would carry over the gap: the odometry noise model times the
//   number of keyframe steps the gap spans, max(1, distance / keyframe_distance) (independent steps add up).
// - rule "unknown" (a keyframe has no reference, live use): the identity with an uninformative covariance
//   (sigma_rot = pi rad, sigma_trans = 1000 m): the factor only keeps the graph connected and says nothing.
#include <optional>
#include <string>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::dataset {

struct GapBridge {
  Pose3 measurement = Pose3::Identity();
  Matrix6 covariance = Matrix6::Identity();
  std::string rule;  ///< "reference" or "unknown"
  double gap_seconds = 0.0;
  double steps = 1.0;  ///< keyframe steps the covariance stands for ("reference")
};

/// The bridge from a keyframe at `before` (stamp, reference pose) to one at `after`.
GapBridge bridgeGap(StampNs before_stamp, const std::optional<Pose3>& before_reference, StampNs after_stamp,
                    const std::optional<Pose3>& after_reference, const Matrix6& odometry_covariance,
                    double keyframe_distance = 2.0);

/// The "unknown" rule's covariance.
Matrix6 unknownBridgeCovariance();

}  // namespace cosmo::dataset
