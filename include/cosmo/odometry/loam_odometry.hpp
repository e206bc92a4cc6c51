#pragma once
// LiDAR-only LOAM odometry at scan rate (spec 4.1): scan lines -> edge / planar features -> robust
// scan-to-local-map registration (last K scans' features) from the best of several initial guesses
// (constant velocity, zero motion, and a coarse yaw search when both fit poorly). Degenerate scans (empty,
// NaN, < 100 points, too few constraints, unconstrained directions) never throw: the result carries a
// warning and the motion model fills in.
#include <optional>
#include <string>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/odometry/feature_extraction.hpp"
#include "cosmo/odometry/feature_registration.hpp"
#include "cosmo/odometry/local_feature_map.hpp"
#include "cosmo/odometry/loam_params.hpp"

namespace cosmo::odometry {

struct OdometryResult {
  Pose3 pose = Pose3::Identity();   ///< sensor pose at scan.stamp in the odometry frame (first scan = identity)
  Pose3 delta = Pose3::Identity();  ///< motion since the previous scan
  bool ok = true;                   ///< false: degenerate input, motion model used (fully or in some directions)
  std::string warning;
  // Diagnostics.
  std::size_t num_points = 0;  ///< valid points organised into scan lines
  std::size_t num_edge_features = 0;
  std::size_t num_planar_features = 0;
  int iterations = 0;
  double inlier_fraction = 0.0;
  std::string initial_guess;  ///< "first", "constant_velocity", "zero_motion", "yaw_search", "motion_model"
};

class LoamOdometry {
 public:
  explicit LoamOdometry(const LoamParams& p = {});
  /// Processes the next scan (stamps should increase; equal or zero stamps are treated as an unknown period).
  OdometryResult update(const Scan& scan);
  const LoamParams& params() const { return params_; }
  /// Features of the last scan (sensor frame), for inspection.
  const LoamFeatures& lastFeatures() const { return last_features_; }
  std::size_t numScans() const { return num_scans_; }

 private:
  struct ScanMotion;
  /// Seconds since the previous scan (0 when unknown); remembers this stamp.
  double advanceClock(StampNs stamp, bool first);
  /// Scan lines and features of `scan` into last_features_ (counts into r).
  void takeFeatures(const Scan& scan, OdometryResult& r);
  /// The first scan: its features start the local map.
  OdometryResult startMap(const Scan& scan, OdometryResult r);
  /// The motion-model result when the scan cannot be registered (too few points or features, empty map).
  std::optional<OdometryResult> fallbackIfUnusable(const Scan& scan, const OdometryResult& r, double period);
  /// The motion as it deskews (x / y / yaw only with deskew_planar_only).
  Pose3 deskewMotion(const Pose3& delta) const;
  ScanMotion predictScanMotion(double period) const;
  /// The better of the constant-velocity and zero-motion guesses.
  Pose3 initialGuess(const ScanMotion& m, OdometryResult& r) const;
  /// On the second scan: the first scan's features deskewed once the motion is known.
  void deskewFirstScanOnce(ScanMotion& m, Pose3& guess);
  FeatureRegistrationResult registerFrom(const ScanMotion& m, const Pose3& start) const;
  /// A coarse yaw search when the registration fits poorly or turned unexpectedly; keeps a clearly better one.
  void searchYawIfPoorFit(ScanMotion& m, const Pose3& guess, FeatureRegistrationResult& reg, OdometryResult& r) const;
  /// The registration becomes the pose (or the motion model, with too few constraints); the map takes the scan.
  OdometryResult accept(const ScanMotion& m, const FeatureRegistrationResult& reg, OdometryResult r);
  void insertIntoMap(const ScanMotion& m, const FeatureRegistrationResult& reg, const Pose3& delta);
  OdometryResult fallback(OdometryResult r, double period, const std::string& why);

  LoamParams params_;
  LocalFeatureMap map_;
  LoamFeatures last_features_;
  std::size_t num_scans_ = 0;
  Pose3 pose_ = Pose3::Identity();
  Pose3 last_delta_ = Pose3::Identity();
  Pose3 last_insert_pose_ = Pose3::Identity();  ///< pose of the newest scan in the local map
  double last_period_ = 0.0;
  StampNs last_stamp_ = 0;
  /// The first scan's features as measured (its motion was unknown when it entered the map): deskewed and
  /// re-inserted once the second scan gives the motion.
  LoamFeatures first_features_;
  bool first_needs_deskew_ = false;
};

}  // namespace cosmo::odometry
