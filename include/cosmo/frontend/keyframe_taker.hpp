#pragma once
// The robot-local step of a front-end between odometry and place recognition (spec 4.2-4.3): the keyframer
// (d_kf) and the keyframe scan it keeps and offers, dewarped to its stamp with the reference trajectory when the
// robot has one, else with the odometry of the sweep (the previous scan's pose and this one), points only,
// without NaN or too-close points. RobotFrontend runs one; OdometryRunAhead runs a copy on each robot's worker
// thread, fed the same poses, so the keyframe scans are ready when the team needs them.

#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/odometry/keyframer.hpp"
#include "cosmo/frontend/frontend_params.hpp"

namespace cosmo::frontend {

class KeyframeTaker {
 public:
  explicit KeyframeTaker(const FrontendParams& params);
  /// Feeds the next scan's odometry pose (stamps increasing): the keyframer's decision.
  odometry::KeyframeDecision update(StampNs stamp, const Pose3& odom_pose);
  /// The keyframe scan of `scan`, the scan last given to update(); `reference`: the robot's sensor trajectory in
  /// the world frame (empty: dewarped with the odometry).
  Scan keyframeScan(const Scan& scan, const Trajectory& reference) const;

 private:
  double min_range_;
  bool dewarp_with_reference_;
  odometry::Keyframer keyframer_;
  Trajectory recent_odometry_;  ///< the odometry of the last two scans (the sweep of the latest one)
};

}  // namespace cosmo::frontend
