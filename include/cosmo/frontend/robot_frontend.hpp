#pragma once
// One robot's front-end (spec section 4), the per-robot node of the shared object graph that both drivers
// (the `frontend` ROS node and the offline TeamRun) drive:
//   scan -> odometry (LOAM, or a pose from an external odometry source) -> keyframer (d_kf) -> dewarp
//   (reference trajectory when given, else odometry) -> PlaceRecognizer (own + per-teammate databases) ->
//   GlobalRegistration of every candidate -> loop-closure measurements stamped with the time they were computed.
// One door per kind of input, add(OwnScan | TeammateScan | ReferencePose | OdometryPose), one result (Step), and
// complete() for the loop closures it started; everything else is set when it is built (FrontendSetup).
// It keeps its dewarped keyframe scans (points only, the radio payload) to offer to teammates. Kept scans and their registration features go to a spill file
// (FrontendParams::spill_keyframes, kept_scan.hpp) and are in memory only while in use, so that its memory does not
// grow with the keyframes; the most recent own keyframe scan stays in memory (it is offered to the radio next).
//
// Measurement convention (what the recorder expects): key1 is always this robot's pose and
// measurement = T_key1^-1 * T_key2, i.e. GlobalRegistration's T_target_source with target = own keyframe scan
// and source = the matched scan. For an intra-robot closure key1 is the newer keyframe (the query).
#include <cstddef>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/odometry/loam_odometry.hpp"
#include "cosmo/frontend/feature_cache.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/frontend/keyframe_taker.hpp"
#include "cosmo/frontend/kept_scan.hpp"
#include "cosmo/frontend/odometry_source.hpp"
#include "cosmo/frontend/registration_pool.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/registration/global_registration.hpp"

namespace cosmo::frontend {

/// A keyframe this robot took.
struct KeyframeRecord {
  char robot = 'a';
  std::size_t index = 0;  ///< from FrontendSetup::first_index (0)
  StampNs stamp = 0;
  Pose3 odom_pose = Pose3::Identity();  ///< sensor pose in this robot's odometry frame
  Pose3 relative = Pose3::Identity();   ///< odometry from the previous keyframe (identity for index 0)
  std::optional<Pose3> reference;       ///< sensor pose in the world frame (reference trajectory)
};

/// What a front-end's stores hold (benchmarks, tests): keyframe scans and ScanContext descriptors.
struct FrontendFootprint {
  std::size_t keyframes = 0;
  std::size_t own_scans = 0, teammate_scans = 0;  ///< stored keyframe scans (each counted once, see footprint())
  std::size_t scan_bytes_in_memory = 0;           ///< points of stored scans held in memory
  std::size_t scan_bytes_spilled = 0;             ///< points of stored scans written to the spill file
  std::size_t descriptor_bytes = 0;               ///< ScanContext descriptors and keys of every database
  FrontendFootprint& operator+=(const FrontendFootprint& o);
};

/// One registered loop-closure candidate (accepted or not).
struct LoopClosureAttempt {
  char owner = 'a';         ///< the robot that computed it (= key1's robot)
  StampNs computed_at = 0;  ///< keyframe stamp, or the time the teammate's scan was received
  char robot1 = 'a';        ///< key1 = (robot1, index1), always the owner's pose
  std::size_t index1 = 0;
  char robot2 = 'a';  ///< key2 = (robot2, index2)
  std::size_t index2 = 0;
  Pose3 measurement = Pose3::Identity();  ///< T_key1^-1 * T_key2
  bool accepted = false;                  ///< the registration gate's verdict (only accepted ones are measurements)
  double descriptor_distance = 1.0;
  std::size_t inliers = 0;
  std::string reason;  ///< the registration's reason ("ok" or why it was rejected)
  bool inter() const { return robot1 != robot2; }
};

/// A candidate whose registration runs on the front-end's RegistrationPool (zero threads: already computed): the
/// attempt without its registration's verdict, and the registration's result to come. RobotFrontend::complete()
/// turns it into the attempt.
struct PendingLoopClosure {
  LoopClosureAttempt attempt;  ///< keys, owner, computed_at, descriptor distance; not yet the measurement
  std::shared_future<registration::RegistrationResult> result;
  bool ready() const;  ///< the result has arrived (complete() will not wait)
};

/// One of the robot's own scans (stamps increasing): its points, or its LOAM odometry and keyframe scan prepared
/// ahead (OdometryRunAhead: a LoamOdometry and a KeyframeTaker with these parameters fed exactly this robot's scans
/// in order), which give the same step as the points.
struct OwnScan {
  StampNs stamp = 0;
  const Scan* points = nullptr;               ///< the scan, sensor frame (nullptr when prepared); not kept
  std::optional<odometry::OdometryResult> loam;         ///< its LOAM result computed elsewhere (used with LOAM odometry)
  std::shared_ptr<const Scan> keyframe_scan;  ///< prepared: its keyframe scan when it is a keyframe

  static OwnScan of(const Scan& scan) { return OwnScan{scan.stamp, &scan, std::nullopt, nullptr}; }
  static OwnScan withLoam(const Scan& scan, const odometry::OdometryResult& loam) { return OwnScan{scan.stamp, &scan, loam, nullptr}; }
  static OwnScan prepared(StampNs stamp, const odometry::OdometryResult& loam, std::shared_ptr<const Scan> keyframe_scan) {
    return OwnScan{stamp, nullptr, loam, std::move(keyframe_scan)};
  }
};

/// A teammate's keyframe scan (points, sensor frame) received at `received_at` (the time its loop closures are
/// computed at).
struct TeammateScan {
  char robot = 'a';
  std::size_t index = 0;
  std::shared_ptr<const KeptScan> kept;  ///< the sender's own kept scan (TeamRun keeps each scan once), or
  std::shared_ptr<const Scan> scan;      ///< the scan itself
  StampNs received_at = 0;

  /// A scan decoded from a message: its invalid points removed.
  static TeammateScan decoded(char robot, std::size_t index, const Scan& scan, StampNs received_at);
  static TeammateScan shared(char robot, std::size_t index, std::shared_ptr<const Scan> scan, StampNs received_at) {
    return TeammateScan{robot, index, nullptr, std::move(scan), received_at};
  }
  static TeammateScan keptBySender(char robot, std::size_t index, std::shared_ptr<const KeptScan> kept,
                                   StampNs received_at) {
    return TeammateScan{robot, index, std::move(kept), nullptr, received_at};
  }
};

/// A reference (world) sensor pose as it arrives (live use); stamps not after the last are ignored.
struct ReferencePose {
  StampNs stamp = 0;
  Pose3 sensor_in_world = Pose3::Identity();
};

/// A pose of an external odometry source (OdometryKind::External), sensor in its odometry frame.
struct OdometryPose {
  StampNs stamp = 0;
  Pose3 sensor_in_odometry = Pose3::Identity();
};

/// What one input produced.
struct Step {
  bool dropped = false;                    ///< a scan that was not processed (no odometry for it, stamp not increasing)
  odometry::OdometryResult odometry;                 ///< a processed scan: pose (sensor, odometry frame) at its stamp
  std::optional<KeyframeRecord> keyframe;  ///< set when the scan became a keyframe
  std::vector<PendingLoopClosure> closures;  ///< complete() each, in order
  std::vector<std::string> notices;          ///< what the driver should tell (odometry fallbacks, dropped inputs)
};

/// Everything a front-end is built with.
struct FrontendSetup {
  FrontendParams params;  ///< params.odometry: which odometry its scans get
  /// The robot's sensor (LiDAR) trajectory in the world frame, in sequence time (may be empty), and how the rest of
  /// it arrives (odometry_source.hpp: whole before the first scan, or pose by pose through add(ReferencePose)).
  Trajectory reference;
  ReferenceArrival reference_arrival = ReferenceArrival::Whole;
  /// The index of its first keyframe (a restarted front-end continues its robot's, so that no index names two poses).
  std::size_t first_index = 0;
  /// Registration features cached here, shared with other front-ends of the process that use the same
  /// registration parameters (TeamRun; same results as an own cache). nullptr: its own.
  std::shared_ptr<FeatureCache> features;
  /// Where the registrations run (nullptr: a pool of zero threads, i.e. inline). The jobs share the feature cache,
  /// which is thread-safe, and hold copies of what they need (the pool may outlive the front-end).
  std::shared_ptr<RegistrationPool> pool;
};

class RobotFrontend {
 public:
  RobotFrontend(char robot, FrontendSetup setup);
  /// LOAM-or-params.odometry front-end with a whole reference, its own caches, registrations inline.
  RobotFrontend(char robot, const FrontendParams& params, Trajectory reference = {});

  /// The next own scan: odometry (OdometrySource) -> keyframer -> place recognition -> registrations started.
  /// Throws std::logic_error when a prepared scan does not match this front-end's keyframer (a keyframe whose scan
  /// was not given, or a keyframe scan given for a scan that is no keyframe) or with reference odometry.
  Step add(const OwnScan& scan);
  /// A teammate's keyframe scan: searched against the own database, stored in that teammate's database; its
  /// candidates' registrations started.
  Step add(const TeammateScan& scan);
  /// A reference pose (pose-by-pose arrival).
  Step add(const ReferencePose& pose);
  /// An external odometry pose.
  Step add(const OdometryPose& pose);
  /// Waits for a pending registration and returns the finished attempt (counted as accepted or rejected): the same
  /// attempt, bit for bit, whichever thread computed it.
  LoopClosureAttempt complete(const PendingLoopClosure& pending);

  char robot() const { return robot_; }
  const FrontendParams& params() const { return params_; }
  /// Dewarped keyframe scan (points only, stamp = keyframe stamp); nullptr for an unknown index. Read back from the
  /// spill file unless in use (the most recent keyframe's always is).
  std::shared_ptr<const Scan> keyframeScan(std::size_t index) const;
  /// The kept keyframe scan (what TeamRun delivers to teammates); nullptr for an unknown index.
  std::shared_ptr<const KeptScan> keptScan(std::size_t index) const;
  /// The spill file of this front-end's kept scans and (unless shared) features; nullptr when not spilling.
  const std::shared_ptr<SpillFile>& spillFile() const { return spill_; }
  const std::vector<KeyframeRecord>& keyframes() const { return keyframes_; }
  std::size_t scansProcessed() const { return scans_; }
  const Pose3& lastOdomPose() const { return last_pose_; }
  StampNs lastStamp() const { return last_stamp_; }
  bool hasReference() const { return !reference_.empty(); }
  const Trajectory& reference() const { return reference_; }
  /// A keyframe's reference pose at `stamp`: within FrontendParams::reference_tolerance_s of the trajectory, else
  /// nullopt.
  std::optional<Pose3> referenceAt(StampNs stamp) const;
  /// Counters.
  std::size_t loopClosuresAccepted() const { return accepted_; }
  std::size_t loopClosuresRejected() const { return rejected_; }
  std::size_t teammateScansReceived() const { return received_; }
  /// What the stores hold; a stored scan already in `seen` (shared with another front-end) is not counted again.
  FrontendFootprint footprint(std::set<const void*>& seen) const;
  /// The registration features' cache (shared with the team's other front-ends in TeamRun).
  const FeatureCache& featureCache() const { return *feature_cache_; }

 private:
  /// The scan's odometry as the OdometrySource chooses it; nullopt: dropped (with a notice in `step`).
  std::optional<odometry::OdometryResult> odometryOf(const OwnScan& scan, Step& step);
  /// `take_keyframe`: the keyframe scan of this scan when it becomes one.
  void afterOdometry(StampNs stamp, odometry::OdometryResult odometry,
                     const std::function<std::shared_ptr<const Scan>()>& take_keyframe, Step& step);
  /// Starts the registration of candidate `c` on the pool.
  PendingLoopClosure registerPair(const place_recognition::LoopCandidate& c, StampNs computed_at);
  std::shared_ptr<const KeptScan> storedScan(char robot, std::size_t index) const;

  char robot_;
  FrontendParams params_;
  Trajectory reference_;
  OdometrySource odometry_source_;
  odometry::LoamOdometry odometry_;
  KeyframeTaker taker_;
  place_recognition::PlaceRecognizer recognizer_;
  registration::GlobalRegistration registration_;

  std::vector<KeyframeRecord> keyframes_;
  std::shared_ptr<SpillFile> spill_;  ///< nullptr: kept scans and features stay in memory
  std::map<std::size_t, std::shared_ptr<const KeptScan>> own_scans_;
  std::map<char, std::map<std::size_t, std::shared_ptr<const KeptScan>>> teammate_scans_;
  std::shared_ptr<const Scan> latest_scan_;  ///< the most recent own keyframe scan, kept in memory
  std::shared_ptr<FeatureCache> feature_cache_;
  std::shared_ptr<RegistrationPool> pool_;

  std::size_t first_index_ = 0;  ///< the index of this front-end's first keyframe
  Pose3 last_pose_ = Pose3::Identity();
  StampNs last_stamp_ = 0;
  std::size_t scans_ = 0, accepted_ = 0, rejected_ = 0, received_ = 0;
};

}  // namespace cosmo::frontend
