#include "cosmo/pipeline/robot_frontend.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace cosmo::pipeline {

RobotFrontend::RobotFrontend(char robot, const FrontendParams& params, Trajectory reference)
    : robot_(robot),
      params_(params),
      reference_(std::move(reference)),
      odometry_(params.loam),
      taker_(params),
      recognizer_(robot, params.place),
      registration_(params.registration),
      spill_(params.spill_keyframes ? std::make_shared<SpillFile>(params.spill_dir) : nullptr),
      feature_cache_(std::make_shared<FeatureCache>(spill_)) {}

std::optional<Pose3> RobotFrontend::referenceAt(StampNs stamp) const {
  if (reference_.empty()) return std::nullopt;
  if (auto p = reference_.at(stamp)) return p;
  const StampNs tol = toStampNs(params_.reference_tolerance_s);
  const StampNs start = reference_.startStamp(), end = reference_.endStamp();
  if ((stamp < start && start - stamp <= tol) || (stamp > end && stamp - end <= tol))
    return reference_.atClamped(stamp);
  return std::nullopt;
}

void RobotFrontend::appendReference(StampNs stamp, const Pose3& sensor_in_world) {
  if (!sensor_in_world.matrix().allFinite()) return;
  if (!reference_.empty() && stamp <= reference_.endStamp()) return;
  reference_.append(stamp, sensor_in_world);
}

ScanOutcome RobotFrontend::processScan(const Scan& scan) { return afterOdometry(scan, odometry_.update(scan)); }

ScanOutcome RobotFrontend::processScan(const Scan& scan, const OdometryResult& loam_result) {
  return afterOdometry(scan, loam_result);
}

ScanOutcome RobotFrontend::processScan(const Scan& scan, const Pose3& external_odom_pose) {
  OdometryResult r;
  r.pose = external_odom_pose;
  r.delta = scans_ == 0 ? Pose3::Identity() : last_pose_.inverse() * external_odom_pose;
  r.initial_guess = "external";
  r.num_points = scan.size();
  if (!external_odom_pose.matrix().allFinite()) {
    r.ok = false;
    r.warning = "external odometry pose is not finite; previous pose kept";
    r.pose = last_pose_;
    r.delta = Pose3::Identity();
  }
  return afterOdometry(scan, r);
}

ScanOutcome RobotFrontend::processPrepared(StampNs stamp, const OdometryResult& loam_result,
                                           std::shared_ptr<const Scan> keyframe_scan) {
  bool taken = false;
  ScanOutcome out = afterOdometry(stamp, loam_result, [&]() {
    if (!keyframe_scan)
      throw std::logic_error(std::string("robot ") + robot_ + ": keyframe " + std::to_string(keyframes_.size() - 1) +
                             " at stamp " + std::to_string(stamp) + " was not prepared");
    taken = true;
    return std::move(keyframe_scan);
  });
  if (keyframe_scan && !taken)
    throw std::logic_error(std::string("robot ") + robot_ + ": a keyframe was prepared for stamp " +
                           std::to_string(stamp) + ", which is none");
  return out;
}

ScanOutcome RobotFrontend::afterOdometry(const Scan& scan, OdometryResult odometry) {
  return afterOdometry(scan.stamp, std::move(odometry),
                       [&]() { return std::make_shared<const Scan>(taker_.keyframeScan(scan, reference_)); });
}

ScanOutcome RobotFrontend::afterOdometry(StampNs stamp, OdometryResult odometry,
                                         const std::function<std::shared_ptr<const Scan>()>& take_keyframe) {
  ScanOutcome out;
  ++scans_;
  last_pose_ = odometry.pose;
  last_stamp_ = stamp;
  out.odometry = odometry;

  const KeyframeDecision kd = taker_.update(stamp, odometry.pose);
  if (!kd.is_keyframe) return out;

  KeyframeRecord kf;
  kf.robot = robot_;
  kf.index = first_index_ + kd.index;
  kf.stamp = stamp;
  kf.odom_pose = odometry.pose;
  kf.relative = kd.index == 0 ? Pose3::Identity() : kd.relative;
  kf.reference = referenceAt(stamp);
  keyframes_.push_back(kf);
  out.keyframe = kf;

  std::shared_ptr<const Scan> kf_scan = take_keyframe();
  const std::vector<LoopCandidate> candidates = recognizer_.addOwnKeyframe(kf.index, *kf_scan);
  own_scans_[kf.index] = std::make_shared<const KeptScan>(kf_scan, spill_);
  latest_scan_ = std::move(kf_scan);
  for (const auto& c : candidates) {
    PendingLoopClosure p = registerPair(c, stamp);
    if (pool_) {
      out.pending_loop_closures.push_back(std::move(p));
    } else {
      out.loop_closures.push_back(completeLoopClosure(p));
    }
  }
  return out;
}

std::vector<LoopClosureAttempt> RobotFrontend::receiveTeammateScan(char teammate, std::size_t index, const Scan& scan,
                                                                   StampNs received_at) {
  auto kept = std::make_shared<Scan>();
  kept->stamp = scan.stamp;
  kept->points = removeInvalidPoints(scan).points;
  return receiveTeammateScan(teammate, index, std::shared_ptr<const Scan>(std::move(kept)), received_at);
}

std::vector<LoopClosureAttempt> RobotFrontend::receiveTeammateScan(char teammate, std::size_t index,
                                                                   std::shared_ptr<const Scan> scan,
                                                                   StampNs received_at) {
  std::vector<LoopClosureAttempt> out;
  for (const auto& p : receiveTeammateScanPending(teammate, index, std::move(scan), received_at))
    out.push_back(completeLoopClosure(p));
  return out;
}

std::vector<PendingLoopClosure> RobotFrontend::receiveTeammateScanPending(char teammate, std::size_t index,
                                                                          std::shared_ptr<const Scan> scan,
                                                                          StampNs received_at) {
  if (!scan) throw std::invalid_argument(std::string("robot ") + robot_ + ": received a null scan");
  auto kept = std::make_shared<const KeptScan>(scan, spill_);  // `scan` stays in use meanwhile: not read back
  return receiveTeammateScanPending(teammate, index, std::move(kept), received_at);
}

std::vector<PendingLoopClosure> RobotFrontend::receiveTeammateScanPending(char teammate, std::size_t index,
                                                                          std::shared_ptr<const KeptScan> scan,
                                                                          StampNs received_at) {
  if (teammate == robot_) throw std::invalid_argument(std::string("robot ") + robot_ + ": received its own scan");
  if (!scan) throw std::invalid_argument(std::string("robot ") + robot_ + ": received a null scan");
  ++received_;
  const std::vector<LoopCandidate> candidates = recognizer_.addTeammateScan(teammate, index, *scan->get());
  teammate_scans_[teammate][index] = std::move(scan);
  std::vector<PendingLoopClosure> out;
  for (const auto& c : candidates) out.push_back(registerPair(c, received_at));
  return out;
}

std::shared_ptr<const Scan> RobotFrontend::keyframeScan(std::size_t index) const {
  const std::shared_ptr<const KeptScan> kept = keptScan(index);
  return kept ? kept->get() : nullptr;
}

std::shared_ptr<const KeptScan> RobotFrontend::keptScan(std::size_t index) const { return storedScan(robot_, index); }

std::shared_ptr<const KeptScan> RobotFrontend::storedScan(char robot, std::size_t index) const {
  if (robot == robot_) {
    auto it = own_scans_.find(index);
    return it == own_scans_.end() ? nullptr : it->second;
  }
  auto t = teammate_scans_.find(robot);
  if (t == teammate_scans_.end()) return nullptr;
  auto it = t->second.find(index);
  return it == t->second.end() ? nullptr : it->second;
}

void RobotFrontend::shareFeatureCache(std::shared_ptr<FeatureCache> cache) {
  if (!cache) throw std::invalid_argument("robot frontend: null feature cache");
  feature_cache_ = std::move(cache);
}

bool PendingLoopClosure::ready() const {
  return result.valid() && result.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

PendingLoopClosure RobotFrontend::registerPair(const LoopCandidate& c, StampNs computed_at) {
  // key1 = the own pose: the query when the query is an own keyframe, else the matched own keyframe.
  PendingLoopClosure p;
  LoopClosureAttempt& a = p.attempt;
  a.owner = robot_;
  a.computed_at = computed_at;
  a.descriptor_distance = c.distance;
  if (c.query_robot == robot_) {
    a.robot1 = robot_;
    a.index1 = c.query_index;
    a.robot2 = c.match_robot;
    a.index2 = c.match_index;
  } else {
    a.robot1 = robot_;
    a.index1 = c.match_index;
    a.robot2 = c.query_robot;
    a.index2 = c.query_index;
  }
  // target = own keyframe scan (key1), source = the other scan (key2): T_target_source = T_key1^-1 T_key2.
  std::shared_ptr<const KeptScan> target = storedScan(a.robot1, a.index1);
  std::shared_ptr<const KeptScan> source = storedScan(a.robot2, a.index2);
  if (!target || !source) throw std::logic_error("robot frontend: no stored scan for a place-recognition candidate");
  // The job holds copies of all it reads, so it runs the same on any thread (and after this front-end is gone).
  std::shared_ptr<FeatureCache> cache = params_.cache_features ? feature_cache_ : nullptr;
  auto job = [registration = registration_, cache = std::move(cache), target = std::move(target),
              source = std::move(source)]() -> RegistrationResult {
    if (!cache) return registration.align(*source->get(), *target->get());
    const auto prepare = [&registration](const Scan& s) { return registration.prepare(s); };
    const std::shared_ptr<const FeatureCloud> target_features = cache->get(target, prepare);
    const std::shared_ptr<const FeatureCloud> source_features = cache->get(source, prepare);
    return registration.align(*source_features, *target_features);
  };
  if (pool_) {
    p.result = pool_->submit(std::move(job));
  } else {
    std::promise<RegistrationResult> done;
    done.set_value(job());
    p.result = done.get_future().share();
  }
  return p;
}

LoopClosureAttempt RobotFrontend::completeLoopClosure(const PendingLoopClosure& pending) {
  if (pending.attempt.owner != robot_)
    throw std::invalid_argument(std::string("robot ") + robot_ + ": completing another robot's loop closure");
  const RegistrationResult& r = pending.result.get();
  LoopClosureAttempt a = pending.attempt;
  a.measurement = r.T_target_source;
  a.inliers = r.final_inliers;
  a.reason = r.reason;
  a.accepted = r.valid && a.measurement.matrix().allFinite();
  if (a.accepted) {
    ++accepted_;
  } else {
    ++rejected_;
  }
  return a;
}

}  // namespace cosmo::pipeline

namespace cosmo::pipeline {

namespace {
std::size_t descriptorBytes(const ScanContextDatabase& db) {
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < db.size(); ++i) {
    const ScanContext& d = db.entry(i).descriptor;
    bytes += sizeof(float) * static_cast<std::size_t>(d.descriptor.size() + d.ring_key.size() + d.sector_key.size());
  }
  return bytes;
}
}  // namespace

FrontendFootprint& FrontendFootprint::operator+=(const FrontendFootprint& o) {
  keyframes += o.keyframes;
  own_scans += o.own_scans;
  teammate_scans += o.teammate_scans;
  scan_bytes_in_memory += o.scan_bytes_in_memory;
  scan_bytes_spilled += o.scan_bytes_spilled;
  descriptor_bytes += o.descriptor_bytes;
  return *this;
}

FrontendFootprint RobotFrontend::footprint(std::set<const void*>& seen) const {
  FrontendFootprint f;
  f.keyframes = keyframes_.size();
  const auto count = [&](const std::shared_ptr<const KeptScan>& s, std::size_t& n) {
    if (!s || !seen.insert(s.get()).second) return;
    ++n;
    f.scan_bytes_in_memory += s->bytesInMemory();
    if (s->spilled()) f.scan_bytes_spilled += s->bytes();
  };
  for (const auto& [i, s] : own_scans_) count(s, f.own_scans);
  for (const auto& [r, scans] : teammate_scans_)
    for (const auto& [i, s] : scans) count(s, f.teammate_scans);
  f.descriptor_bytes = descriptorBytes(recognizer_.ownDatabase());
  for (const auto& [r, scans] : teammate_scans_)
    if (const ScanContextDatabase* db = recognizer_.teammateDatabase(r)) f.descriptor_bytes += descriptorBytes(*db);
  return f;
}

}  // namespace cosmo::pipeline
