#pragma once
// Which odometry a robot's scan gets (spec section 4.1), decided here for every driver (the front-end node, the
// offline TeamRun and through it cosmo_generate and the lockstep launch):
//   loam       LOAM on the scan (or its LOAM result computed ahead, OdometryRunAhead);
//   reference  the robot's reference (world) sensor pose at the scan stamp, LOAM where there is none;
//   external   the pose of another odometry source (a robot's own odometry topic) interpolated at the scan
//              stamp; a scan with no such pose is dropped.
// The reference rule depends on how the reference reaches the front-end, and says so once:
//   whole        (offline, lockstep: the trial's trajectory, known before the first scan) the pose held at the
//                nearest end outside the trajectory: a trial whose scans outlast its reference keeps one odometry
//                frame to its end instead of switching to LOAM's;
//   pose by pose (real time: reference_pose messages) held at most FrontendParams::reference_tolerance_s past an
//                end: a scan beyond the newest pose may only be ahead of it, and a reference that stopped arriving
//                must not freeze the robot, so farther out the scan takes LOAM (with a notice).
#include <optional>
#include <string>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/frontend/external_odometry.hpp"

namespace cosmo::frontend {

enum class OdometryKind { Loam, Reference, External };

/// "loam", "reference" or "external"; anything else throws std::invalid_argument naming the choices.
OdometryKind parseOdometryKind(const std::string& name);
const char* odometryKindName(OdometryKind kind);

/// How the reference trajectory reaches the front-end (see above).
enum class ReferenceArrival { Whole, PoseByPose };

/// The odometry of one scan.
struct OdometryChoice {
  enum class Use { Loam, Pose, Drop };
  Use use = Use::Loam;
  Pose3 pose = Pose3::Identity();  ///< Use::Pose: the sensor pose in the odometry frame
  std::string notice;              ///< why the scan does not get what the kind asks for (empty when it does)
};

class OdometrySource {
 public:
  OdometrySource(OdometryKind kind, ReferenceArrival arrival, StampNs reference_tolerance);

  OdometryKind kind() const { return kind_; }
  ReferenceArrival arrival() const { return arrival_; }
  /// A pose of the external odometry source (kept for the scans that take their pose from it).
  void addExternalPose(StampNs stamp, const Pose3& pose) { external_.add(stamp, pose); }
  /// The odometry of the scan at `stamp`; `reference` is the robot's reference trajectory as known now.
  OdometryChoice choose(StampNs stamp, const Trajectory& reference) const;

 private:
  OdometryKind kind_;
  ReferenceArrival arrival_;
  StampNs reference_tolerance_;
  ExternalOdometry external_;
};

}  // namespace cosmo::frontend
