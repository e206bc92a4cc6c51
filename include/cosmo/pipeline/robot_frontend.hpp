#pragma once
// One robot's front-end (spec section 4), the per-robot node of the shared object graph that both drivers
// (the `frontend` ROS node and the offline TeamRun) drive:
//   scan -> odometry (LOAM, or a pose from an external odometry source) -> keyframer (d_kf) -> dewarp
//   (reference trajectory when given, else odometry) -> PlaceRecognizer (own + per-teammate databases) ->
//   GlobalRegistration of every candidate -> loop-closure measurements stamped with the time they were computed.
// It keeps its dewarped keyframe scans (points only, the radio payload) to offer to teammates, and takes
// teammates' scans with receiveTeammateScan(). Kept scans and their registration features go to a spill file
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
#include "cosmo/pipeline/feature_cache.hpp"
#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/keyframe_taker.hpp"
#include "cosmo/pipeline/kept_scan.hpp"
#include "cosmo/pipeline/registration_pool.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/registration/global_registration.hpp"

namespace cosmo::pipeline {

/// A keyframe this robot took.
struct KeyframeRecord {
  char robot = 'a';
  std::size_t index = 0;  ///< from 0, or from RobotFrontend::numberKeyframesFrom()
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

/// A candidate whose registration runs on a RegistrationPool: the attempt without its registration's verdict,
/// and the registration's result to come. RobotFrontend::completeLoopClosure() turns it into the attempt.
struct PendingLoopClosure {
  LoopClosureAttempt attempt;  ///< keys, owner, computed_at, descriptor distance; not yet the measurement
  std::shared_future<RegistrationResult> result;
  bool ready() const;  ///< the result has arrived (completeLoopClosure() will not wait)
};

/// What one scan produced.
struct ScanOutcome {
  OdometryResult odometry;                                ///< pose (sensor, odometry frame) at the scan stamp
  std::optional<KeyframeRecord> keyframe;                 ///< set when the scan became a keyframe
  std::vector<LoopClosureAttempt> loop_closures;          ///< registered inline (no RegistrationPool set)
  std::vector<PendingLoopClosure> pending_loop_closures;  ///< with a RegistrationPool, instead of loop_closures
};

class RobotFrontend {
 public:
  /// `reference`: the robot's sensor (LiDAR) trajectory in the world frame, in sequence time (may be empty).
  RobotFrontend(char robot, const FrontendParams& params, Trajectory reference = {});

  /// Next scan (sensor frame, stamps increasing), odometry by LOAM.
  ScanOutcome processScan(const Scan& scan);
  /// Next scan with its sensor pose from an external odometry source (any fixed odometry frame).
  ScanOutcome processScan(const Scan& scan, const Pose3& external_odom_pose);
  /// Next scan with LOAM odometry computed elsewhere (OdometryRunAhead: a LoamOdometry with these parameters fed
  /// exactly this robot's scans in order); the same outcome as processScan(scan).
  ScanOutcome processScan(const Scan& scan, const OdometryResult& loam_result);
  /// The next scan known by its stamp, with its LOAM odometry and, when it is a keyframe, the keyframe scan made
  /// from it by a KeyframeTaker fed the same poses (OdometryRunAhead): the same outcome as processScan(scan).
  /// Throws std::logic_error when this front-end takes a keyframe whose scan was not given, or a scan was given
  /// for a scan that is no keyframe.
  ScanOutcome processPrepared(StampNs stamp, const OdometryResult& loam_result,
                              std::shared_ptr<const Scan> keyframe_scan);
  /// A teammate's keyframe scan (points, sensor frame) received at `received_at`: searched against the own
  /// database, stored in that teammate's database; returns the registered candidates.
  std::vector<LoopClosureAttempt> receiveTeammateScan(char teammate, std::size_t index, const Scan& scan,
                                                      StampNs received_at);
  /// The same sharing the scan (the offline driver hands the sender's own copy: xz is lossless).
  std::vector<LoopClosureAttempt> receiveTeammateScan(char teammate, std::size_t index,
                                                      std::shared_ptr<const Scan> scan, StampNs received_at);
  /// The same with the registrations left pending (on the RegistrationPool when one is set, else computed
  /// already); complete each with completeLoopClosure(), in order.
  std::vector<PendingLoopClosure> receiveTeammateScanPending(char teammate, std::size_t index,
                                                             std::shared_ptr<const Scan> scan, StampNs received_at);
  /// The same keeping the sender's own KeptScan (TeamRun: the team keeps the scan and its features once).
  std::vector<PendingLoopClosure> receiveTeammateScanPending(char teammate, std::size_t index,
                                                             std::shared_ptr<const KeptScan> scan, StampNs received_at);
  /// Waits for a pending registration and returns the finished attempt (counted as accepted or rejected).
  /// The same attempt, bit for bit, as the inline registration gives.
  LoopClosureAttempt completeLoopClosure(const PendingLoopClosure& pending);

  /// Registrations run on `pool` from now on (nullptr: inline, the default): ScanOutcome then carries
  /// pending_loop_closures instead of loop_closures. The jobs share this front-end's feature cache, which is
  /// thread-safe, and hold copies of what they need (the pool may outlive the front-end).
  void setRegistrationPool(std::shared_ptr<RegistrationPool> pool) { pool_ = std::move(pool); }

  /// Registration features cached in `cache` from now on, shared with other front-ends of this process that use
  /// the same registration parameters (TeamRun); the results are the same as with the own cache. (Give it a
  /// spill file, e.g. spillFile(), to keep the features out of memory.)
  void shareFeatureCache(std::shared_ptr<FeatureCache> cache);

  /// Numbers this front-end's keyframes from `first` instead of 0 (a restarted front-end continues its robot's
  /// indices, so that no index names two poses); before the first scan.
  void numberKeyframesFrom(std::size_t first) { first_index_ = first; }

  /// Appends a reference (world) sensor pose as it arrives (live use); stamps not after the last are ignored.
  void appendReference(StampNs stamp, const Pose3& sensor_in_world);

  char robot() const { return robot_; }
  const FrontendParams& params() const { return params_; }
  /// Dewarped keyframe scan (points only, stamp = keyframe stamp); nullptr for an unknown index. Read back from the
  /// spill file unless in use (the most recent keyframe's always is).
  std::shared_ptr<const Scan> keyframeScan(std::size_t index) const;
  std::shared_ptr<const Scan> keyframeScanShared(std::size_t index) const { return keyframeScan(index); }
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
  /// Reference pose at `stamp` (within the tolerance), else nullopt.
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
  /// `take_keyframe`: the keyframe scan of this scan when it becomes one.
  ScanOutcome afterOdometry(StampNs stamp, OdometryResult odometry,
                            const std::function<std::shared_ptr<const Scan>()>& take_keyframe);
  ScanOutcome afterOdometry(const Scan& scan, OdometryResult odometry);
  /// Starts the registration of candidate `c` (on the pool, else inline).
  PendingLoopClosure registerPair(const LoopCandidate& c, StampNs computed_at);
  std::shared_ptr<const KeptScan> storedScan(char robot, std::size_t index) const;

  char robot_;
  FrontendParams params_;
  Trajectory reference_;
  LoamOdometry odometry_;
  KeyframeTaker taker_;
  PlaceRecognizer recognizer_;
  GlobalRegistration registration_;

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

}  // namespace cosmo::pipeline
