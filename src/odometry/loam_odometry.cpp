#include "cosmo/odometry/loam_odometry.hpp"

#include <cmath>
#include <optional>

#include "cosmo/odometry/continuous_rotation_refine.hpp"
#include "cosmo/odometry/dewarp.hpp"
#include "cosmo/odometry/feature_registration.hpp"
#include "cosmo/odometry/motion_model.hpp"
#include "cosmo/odometry/scan_lines.hpp"

namespace cosmo::odometry {
namespace {
constexpr double kPi = 3.14159265358979323846;

/// The fewest valid points a scan is registered with.
std::size_t minPoints(const LoamParams& p) { return static_cast<std::size_t>(p.min_scan_points); }

std::vector<Eigen::Vector3d> transformed(const Pose3& T, const std::vector<Eigen::Vector3d>& pts) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back(T * p);
  return out;
}
}  // namespace

LoamOdometry::LoamOdometry(const LoamParams& p)
    : params_(p),
      map_(static_cast<std::size_t>(std::max(1, p.num_local_map_scans)), p.map_edge_voxel_size,
           p.map_planar_voxel_size) {}

OdometryResult LoamOdometry::fallback(OdometryResult r, double period, const std::string& why) {
  const Pose3 delta = predictMotion(last_delta_, last_period_, period);
  r.delta = delta;
  r.pose = orthonormalized(pose_ * delta);
  r.ok = false;
  r.warning = why + "; motion model used";
  r.initial_guess = "motion_model";
  pose_ = r.pose;
  if (period > 0.0) last_period_ = period;
  return r;
}

/// What one scan's registration works with.
struct LoamOdometry::ScanMotion {
  double period = 0.0;     ///< s since the previous scan (0: unknown)
  bool has_times = false;  ///< the features carry point times and can be deskewed
  Pose3 cv_delta;          ///< constant-velocity prediction of the motion over the sweep
  Pose3 deskew_delta;      ///< the motion the features are deskewed with
  std::size_t stride = 1;  ///< feature subsample for scoring guesses
};

OdometryResult LoamOdometry::update(const Scan& scan) {
  OdometryResult r;
  const bool first = (num_scans_ == 0);
  ++num_scans_;
  const double period = advanceClock(scan.stamp, first);
  takeFeatures(scan, r);
  if (first) return startMap(scan, r);
  if (std::optional<OdometryResult> unusable = fallbackIfUnusable(scan, r, period)) return *unusable;

  ScanMotion m = predictScanMotion(period);
  Pose3 guess = initialGuess(m, r);
  deskewFirstScanOnce(m, guess);
  FeatureRegistrationResult reg = registerFrom(m, guess);
  searchYawIfPoorFit(m, guess, reg, r);
  return accept(m, reg, r);
}

double LoamOdometry::advanceClock(StampNs stamp, bool first) {
  double period = 0.0;
  if (!first && stamp > last_stamp_ && last_stamp_ > 0) period = toSeconds(stamp - last_stamp_);
  if (stamp > 0) last_stamp_ = stamp;
  return period;
}

void LoamOdometry::takeFeatures(const Scan& scan, OdometryResult& r) {
  const ScanLines lines = organizeScanLines(scan, params_);
  r.num_points = lines.numPoints();
  last_features_ = r.num_points >= minPoints(params_) ? extractFeatures(lines, params_) : LoamFeatures{};
  thinPlanarFeatures(last_features_, params_.planar_feature_voxel_size);
  r.num_edge_features = last_features_.edge_points.size();
  r.num_planar_features = last_features_.planar_points.size();
}

OdometryResult LoamOdometry::startMap(const Scan& scan, OdometryResult r) {
  r.initial_guess = "first";
  if (r.num_points < minPoints(params_)) {
    r.ok = false;
    r.warning = "first scan has only " + std::to_string(r.num_points) + " valid points (of " +
                std::to_string(scan.size()) + "); odometry starts at identity with an empty map";
  } else {
    map_.add(last_features_.edge_points, last_features_.planar_points);
    first_features_ = last_features_;
    first_needs_deskew_ =
        params_.deskew && (!first_features_.edge_time.empty() || !first_features_.planar_time.empty());
  }
  return r;
}

std::optional<OdometryResult> LoamOdometry::fallbackIfUnusable(const Scan& scan, const OdometryResult& r,
                                                               double period) {
  if (r.num_points < minPoints(params_))
    return fallback(
        r, period,
        "scan has only " + std::to_string(r.num_points) + " valid points (of " + std::to_string(scan.size()) + ")");
  if (last_features_.size() < static_cast<std::size_t>(params_.min_correspondences))
    return fallback(r, period, "scan has only " + std::to_string(last_features_.size()) + " features");
  if (map_.empty()) {
    OdometryResult out = fallback(r, period, "local map is empty");
    map_.add(transformed(out.pose, last_features_.edge_points), transformed(out.pose, last_features_.planar_points));
    last_insert_pose_ = out.pose;
    return out;
  }
  return std::nullopt;
}

Pose3 LoamOdometry::deskewMotion(const Pose3& delta) const {
  // With deskew_planar_only, only the x / y / yaw part of the motion deskews (see LoamParams).
  if (!params_.deskew_planar_only) return delta;
  Vector6 xi = logSE3(delta);
  xi[0] = xi[1] = 0.0;  // roll, pitch rates
  xi[5] = 0.0;          // vertical velocity
  return expSE3(xi);
}

LoamOdometry::ScanMotion LoamOdometry::predictScanMotion(double period) const {
  ScanMotion m;
  m.period = period;
  m.cv_delta = predictMotion(last_delta_, last_period_, period);
  m.stride = std::max<std::size_t>(1, last_features_.size() / static_cast<std::size_t>(params_.guess_score_features));
  m.has_times =
      params_.deskew && period > 0.0 && (!last_features_.edge_time.empty() || !last_features_.planar_time.empty());
  // Deskew motion of this scan: the constant-velocity prediction (the previous scan's estimated motion), not
  // the scan's own estimate. Deskewing with the own estimate, iterated to self-consistency, feeds the deskew
  // errors of the map's scans back into the estimate: a period-2 oscillation of the scan-to-scan motion that
  // grew without bound on fast trials (test LoamSynthetic.AcceleratingTrialDoesNotOscillate). With the
  // prediction, this scan and the previous one (inserted with its final estimate = this prediction) share the
  // same deskew error, which cancels in the registration.
  m.deskew_delta = deskewMotion(m.cv_delta);
  return m;
}

Pose3 LoamOdometry::initialGuess(const ScanMotion& m, OdometryResult& r) const {
  // Constant velocity and zero motion, scored on a feature subsample: the constant-velocity guess with the
  // features deskewed by that motion, zero motion with the raw ones.
  Pose3 guess = pose_ * m.cv_delta;
  LoamFeatures cv_features = last_features_;
  if (m.has_times) {
    deskewFeatures(last_features_, deskewMotion(m.cv_delta), m.period, cv_features.edge_points,
                   cv_features.planar_points);
  }
  double best = scorePose(cv_features, map_, guess, params_, m.stride);
  r.initial_guess = "constant_velocity";
  const bool cv_is_zero = logSE3(m.cv_delta).norm() < 1e-6;
  if (!cv_is_zero && best < params_.zero_motion_guess_below) {
    const double s0 = scorePose(last_features_, map_, pose_, params_, m.stride);
    if (s0 > best) {
      best = s0;
      guess = pose_;
      r.initial_guess = "zero_motion";
    }
  }
  return guess;
}

void LoamOdometry::deskewFirstScanOnce(ScanMotion& m, Pose3& guess) {
  // Second scan against a first scan that could not be deskewed: both are equally distorted, so register them
  // raw first and deskew the first scan with that motion.
  if (first_needs_deskew_ && m.has_times && map_.numScans() == 1) {
    const FeatureRegistrationResult raw = registerFeatures(last_features_, map_, guess, params_, std::nullopt);
    const Pose3 delta = deskewMotion(pose_.inverse() * raw.pose);
    std::vector<Eigen::Vector3d> e0, p0;
    deskewFeatures(first_features_, delta, m.period, e0, p0);
    map_.clear();
    map_.add(transformed(pose_, e0), transformed(pose_, p0));
    guess = raw.pose;
    m.deskew_delta = delta;
  }
  first_needs_deskew_ = false;
}

FeatureRegistrationResult LoamOdometry::registerFrom(const ScanMotion& m, const Pose3& start) const {
  // Registration from a guess, the features deskewed with m.deskew_delta. Only when the estimate differs from
  // that motion by more than deskew_reestimate_translation / _rotation (an unexpected motion: a sudden turn or
  // stop, a dropped scan) is it registered again, deskewed with the estimate: a few Gauss-Newton steps on the
  // first registration's correspondences (deskew_refine_steps), or a full registration when that is 0.
  std::optional<DeskewReference> deskew;
  if (m.has_times) deskew = DeskewReference{m.deskew_delta, m.period};
  FeatureRegistrationResult reg = registerFeatures(last_features_, map_, start, params_, deskew);
  for (int pass = 0; m.has_times && pass < params_.deskew_reestimate_passes; ++pass) {
    const Pose3 estimate = deskewMotion(pose_.inverse() * reg.pose);
    const Vector6 change = logSE3(deskew->delta.inverse() * estimate);
    if (change.head<3>().norm() < params_.deskew_reestimate_rotation_deg * kPi / 180.0 &&
        change.tail<3>().norm() < params_.deskew_reestimate_translation)
      break;
    if (params_.deskew_refine_steps > 0 && change.tail<3>().norm() < params_.deskew_reestimate_translation) {
      // Only the rotation was not predicted (a walker's sway). The translation stays the prediction's:
      // deskewing with the own translation feeds back into it (a period-2 oscillation).
      if (params_.deskew_rotation_tie > 0.0 && !params_.deskew_planar_only &&
          change.head<3>().norm() < params_.deskew_rotation_max_correction_deg * kPi / 180.0 &&
          Eigen::AngleAxisd(deskew->delta.linear()).angle() < params_.deskew_rotation_max_sweep_deg * kPi / 180.0) {
        // The rotation over the sweep estimated with the pose, its start tied to the previous scan's pose:
        // the features' deskew then agrees with the estimate, nothing left to re-check.
        reg = refineContinuousRotation(last_features_, std::move(reg), params_, pose_, deskew->delta, m.period,
                                       params_.deskew_rotation_tie, params_.deskew_refine_steps);
        break;
      }
      // Otherwise (or in a fast turn): re-deskew once with the estimated rotation, then a few Gauss-Newton
      // steps on the same map lines / planes.
      Pose3 mixed = estimate;
      mixed.translation() = deskew->delta.translation();
      deskew = DeskewReference{mixed, m.period};
      reg = refineRedeskewed(last_features_, std::move(reg), params_, *deskew, params_.deskew_refine_steps);
    } else {
      deskew = DeskewReference{estimate, m.period};
      reg = registerFeatures(last_features_, map_, reg.pose, params_, deskew);
    }
  }
  return reg;
}

void LoamOdometry::searchYawIfPoorFit(ScanMotion& m, const Pose3& guess, FeatureRegistrationResult& reg,
                                      OdometryResult& r) const {
  // Large unexpected motion (fast turns, low scan rates): when the result fits poorly, try a coarse yaw
  // search around the guess and keep its registration only if it clearly fits better. A candidate is a motion
  // hypothesis: its features are deskewed with that motion before they are scored (a scan taken during a fast
  // turn is distorted by it, and no rigid yaw fits the raw points), and its registration starts deskewed with it.
  const double turned_deg = Eigen::AngleAxisd((guess.inverse() * reg.pose).linear()).angle() * 180.0 / kPi;
  const bool unpredicted_turn =
      params_.yaw_search_correction_deg > 0.0 && turned_deg >= params_.yaw_search_correction_deg;
  if (!((reg.inlier_fraction < params_.min_guess_inlier_fraction || unpredicted_turn) &&
        params_.yaw_search_step_deg > 0.0))
    return;
  const double base = scorePose(last_features_, map_, reg.pose, params_, m.stride);
  LoamFeatures deskewed = last_features_;
  auto scoreMotion = [&](const Pose3& cand) {
    if (!m.has_times) return scorePose(last_features_, map_, cand, params_, m.stride);
    deskewFeatures(last_features_, deskewMotion(pose_.inverse() * cand), m.period, deskewed.edge_points,
                   deskewed.planar_points);
    return scorePose(deskewed, map_, cand, params_, m.stride);
  };
  double best_yaw_score = base;
  Pose3 best_yaw = guess;
  for (double yaw = params_.yaw_search_step_deg; yaw <= params_.yaw_search_max_deg + 1e-9;
       yaw += params_.yaw_search_step_deg) {
    for (double sign : {1.0, -1.0}) {
      const Pose3 cand = guess * makePose(0, 0, 0, 0, 0, sign * yaw * kPi / 180.0);
      const double sc = scoreMotion(cand);
      if (sc > best_yaw_score) {
        best_yaw_score = sc;
        best_yaw = cand;
      }
    }
  }
  if (!(best_yaw_score > base + params_.yaw_search_min_gain)) return;
  const Pose3 predicted_deskew = m.deskew_delta;
  m.deskew_delta = deskewMotion(pose_.inverse() * best_yaw);
  const FeatureRegistrationResult alt = registerFrom(m, best_yaw);
  const double margin = unpredicted_turn ? params_.yaw_search_margin_after_turn : params_.yaw_search_margin;
  if (alt.inlier_fraction > reg.inlier_fraction + margin) {
    reg = alt;
    r.initial_guess = "yaw_search";
  } else {
    m.deskew_delta = predicted_deskew;
  }
}

OdometryResult LoamOdometry::accept(const ScanMotion& m, const FeatureRegistrationResult& reg, OdometryResult r) {
  r.iterations = reg.iterations;
  r.inlier_fraction = reg.inlier_fraction;
  const std::size_t ncons = reg.num_edge_constraints + reg.num_plane_constraints;
  if (ncons < static_cast<std::size_t>(params_.min_correspondences))
    return fallback(r, m.period, "only " + std::to_string(ncons) + " feature correspondences with the local map");

  r.pose = reg.pose;
  r.delta = pose_.inverse() * reg.pose;
  if (reg.degenerate_directions > 0) {
    r.ok = false;
    r.warning = "degenerate geometry: " + std::to_string(reg.degenerate_directions) +
                " of 6 directions unconstrained, kept from the initial guess (motion model)";
  }
  pose_ = r.pose;
  last_delta_ = r.delta;
  if (m.period > 0.0) last_period_ = m.period;
  insertIntoMap(m, reg, r.delta);
  return r;
}

void LoamOdometry::insertIntoMap(const ScanMotion& m, const FeatureRegistrationResult& reg, const Pose3& delta) {
  // This scan's features, deskewed with the final motion (its rotation over the sweep, when that was estimated).
  std::vector<Eigen::Vector3d> edges, planes;
  if (m.has_times) {
    Pose3 sweep = deskewMotion(delta);
    if (reg.sweep_rotation) sweep.linear() = *reg.sweep_rotation;
    deskewFeatures(last_features_, sweep, m.period, edges, planes);
  } else {
    edges = last_features_.edge_points;
    planes = last_features_.planar_points;
  }
  // A sensor that has not moved since the last inserted scan would put copies of the same points in the map
  // (a standing start: three identical scans, plane fits on duplicate neighbours fail); the map keeps its scans.
  const Pose3 since_insert = last_insert_pose_.inverse() * pose_;
  if (since_insert.translation().norm() < params_.map_insert_min_translation &&
      Eigen::AngleAxisd(since_insert.linear()).angle() < params_.map_insert_min_rotation_deg * kPi / 180.0)
    return;
  map_.add(transformed(pose_, edges), transformed(pose_, planes));
  last_insert_pose_ = pose_;
}

}  // namespace cosmo::odometry
