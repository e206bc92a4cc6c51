#include "cosmo/frontend/robot_frontend.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace cosmo::frontend {

RobotFrontend::RobotFrontend(char robot, FrontendSetup setup)
    : robot_(robot),
      params_(std::move(setup.params)),
      reference_(std::move(setup.reference)),
      odometry_source_(params_.odometry, setup.reference_arrival, toStampNs(params_.reference_tolerance_s)),
      odometry_(params_.loam),
      taker_(params_),
      recognizer_(robot, params_.place),
      registration_(params_.registration),
      spill_(params_.spill_keyframes ? std::make_shared<SpillFile>(params_.spill_dir) : nullptr),
      feature_cache_(setup.features ? std::move(setup.features) : std::make_shared<FeatureCache>(spill_)),
      pool_(setup.pool ? std::move(setup.pool) : std::make_shared<RegistrationPool>(0)),
      first_index_(setup.first_index) {}

RobotFrontend::RobotFrontend(char robot, const FrontendParams& params, Trajectory reference)
    : RobotFrontend(robot, FrontendSetup{params, std::move(reference)}) {}

std::optional<Pose3> RobotFrontend::referenceAt(StampNs stamp) const {
  return reference_.atWithin(stamp, toStampNs(params_.reference_tolerance_s));
}

Step RobotFrontend::add(const ReferencePose& pose) {
  Step step;
  if (!pose.sensor_in_world.matrix().allFinite()) {
    step.notices.push_back("reference pose at " + std::to_string(pose.stamp) + " is not finite; ignored");
  } else if (!reference_.empty() && pose.stamp <= reference_.endStamp()) {
    step.notices.push_back("reference pose at " + std::to_string(pose.stamp) + " is not after the last; ignored");
  } else {
    reference_.append(pose.stamp, pose.sensor_in_world);
  }
  return step;
}

Step RobotFrontend::add(const OdometryPose& pose) {
  odometry_source_.addExternalPose(pose.stamp, pose.sensor_in_odometry);
  return {};
}

std::optional<odometry::OdometryResult> RobotFrontend::odometryOf(const OwnScan& scan, Step& step) {
  const OdometryChoice choice = odometry_source_.choose(scan.stamp, reference_);
  if (!choice.notice.empty()) step.notices.push_back(choice.notice);
  switch (choice.use) {
    case OdometryChoice::Use::Drop: return std::nullopt;
    case OdometryChoice::Use::Loam: {
      if (scan.loam) return *scan.loam;
      odometry::OdometryResult r = odometry_.update(*scan.points);
      if (!r.ok) step.notices.push_back("odometry: " + r.warning);
      return r;
    }
    case OdometryChoice::Use::Pose: break;
  }
  if (!scan.points)
    throw std::logic_error(std::string("robot ") + robot_ + ": a prepared scan carries LOAM odometry, but this " +
                           "front-end takes its odometry from " + odometryKindName(odometry_source_.kind()));
  odometry::OdometryResult r;
  r.pose = choice.pose;
  r.delta = scans_ == 0 ? Pose3::Identity() : last_pose_.inverse() * choice.pose;
  r.initial_guess = "external";
  r.num_points = scan.points->size();
  if (!choice.pose.matrix().allFinite()) {
    r.ok = false;
    r.warning = "external odometry pose is not finite; previous pose kept";
    r.pose = last_pose_;
    r.delta = Pose3::Identity();
  }
  return r;
}

Step RobotFrontend::add(const OwnScan& scan) {
  Step step;
  if (!scan.points && !scan.loam)
    throw std::invalid_argument(std::string("robot ") + robot_ + ": a scan with neither points nor odometry");
  if (scans_ > 0 && scan.stamp <= last_stamp_) {
    step.dropped = true;
    step.notices.push_back("stamp not increasing, scan dropped");
    return step;
  }
  std::optional<odometry::OdometryResult> odometry = odometryOf(scan, step);
  if (!odometry) {
    step.dropped = true;
    return step;
  }
  if (scan.points) {
    afterOdometry(scan.stamp, std::move(*odometry),
                  [&]() { return std::make_shared<const Scan>(taker_.keyframeScan(*scan.points, reference_)); }, step);
    return step;
  }
  bool taken = false;
  afterOdometry(
      scan.stamp, std::move(*odometry),
      [&]() {
        if (!scan.keyframe_scan)
          throw std::logic_error(std::string("robot ") + robot_ + ": keyframe " +
                                 std::to_string(keyframes_.size() - 1) + " at stamp " + std::to_string(scan.stamp) +
                                 " was not prepared");
        taken = true;
        return scan.keyframe_scan;
      },
      step);
  if (scan.keyframe_scan && !taken)
    throw std::logic_error(std::string("robot ") + robot_ + ": a keyframe was prepared for stamp " +
                           std::to_string(scan.stamp) + ", which is none");
  return step;
}

void RobotFrontend::afterOdometry(StampNs stamp, odometry::OdometryResult odometry,
                                  const std::function<std::shared_ptr<const Scan>()>& take_keyframe, Step& step) {
  ++scans_;
  last_pose_ = odometry.pose;
  last_stamp_ = stamp;
  step.odometry = odometry;

  const odometry::KeyframeDecision kd = taker_.update(stamp, odometry.pose);
  if (!kd.is_keyframe) return;

  KeyframeRecord kf;
  kf.robot = robot_;
  kf.index = first_index_ + kd.index;
  kf.stamp = stamp;
  kf.odom_pose = odometry.pose;
  kf.relative = kd.index == 0 ? Pose3::Identity() : kd.relative;
  kf.reference = referenceAt(stamp);
  keyframes_.push_back(kf);
  step.keyframe = kf;

  std::shared_ptr<const Scan> kf_scan = take_keyframe();
  const std::vector<place_recognition::LoopCandidate> candidates = recognizer_.addOwnKeyframe(kf.index, *kf_scan);
  own_scans_[kf.index] = std::make_shared<const KeptScan>(kf_scan, spill_);
  latest_scan_ = std::move(kf_scan);
  for (const auto& c : candidates) step.closures.push_back(registerPair(c, stamp));
}

TeammateScan TeammateScan::decoded(char robot, std::size_t index, const Scan& scan, StampNs received_at) {
  auto kept = std::make_shared<Scan>();
  kept->stamp = scan.stamp;
  kept->points = removeInvalidPoints(scan).points;
  return shared(robot, index, std::shared_ptr<const Scan>(std::move(kept)), received_at);
}

Step RobotFrontend::add(const TeammateScan& in) {
  if (in.robot == robot_) throw std::invalid_argument(std::string("robot ") + robot_ + ": received its own scan");
  if (!in.kept && !in.scan) throw std::invalid_argument(std::string("robot ") + robot_ + ": received a null scan");
  // `in.scan` stays in use meanwhile: not read back
  std::shared_ptr<const KeptScan> kept = in.kept ? in.kept : std::make_shared<const KeptScan>(in.scan, spill_);
  ++received_;
  const std::vector<place_recognition::LoopCandidate> candidates = recognizer_.addTeammateScan(in.robot, in.index, *kept->get());
  teammate_scans_[in.robot][in.index] = std::move(kept);
  Step step;
  for (const auto& c : candidates) step.closures.push_back(registerPair(c, in.received_at));
  return step;
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

bool PendingLoopClosure::ready() const {
  return result.valid() && result.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

PendingLoopClosure RobotFrontend::registerPair(const place_recognition::LoopCandidate& c, StampNs computed_at) {
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
              source = std::move(source)]() -> registration::RegistrationResult {
    if (!cache) return registration.align(*source->get(), *target->get());
    const auto prepare = [&registration](const Scan& s) { return registration.prepare(s); };
    const std::shared_ptr<const registration::FeatureCloud> target_features = cache->get(target, prepare);
    const std::shared_ptr<const registration::FeatureCloud> source_features = cache->get(source, prepare);
    return registration.align(*source_features, *target_features);
  };
  p.result = pool_->submit(std::move(job));
  return p;
}

LoopClosureAttempt RobotFrontend::complete(const PendingLoopClosure& pending) {
  if (pending.attempt.owner != robot_)
    throw std::invalid_argument(std::string("robot ") + robot_ + ": completing another robot's loop closure");
  const registration::RegistrationResult& r = pending.result.get();
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

}  // namespace cosmo::frontend

namespace cosmo::frontend {

namespace {
std::size_t descriptorBytes(const place_recognition::ScanContextDatabase& db) {
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < db.size(); ++i) {
    const place_recognition::ScanContext& d = db.entry(i).descriptor;
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
    if (const place_recognition::ScanContextDatabase* db = recognizer_.teammateDatabase(r)) f.descriptor_bytes += descriptorBytes(*db);
  return f;
}

}  // namespace cosmo::frontend
