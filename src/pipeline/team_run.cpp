#include "cosmo/pipeline/team_run.hpp"

#include <cmath>
#include <stdexcept>

#include "cosmo/comm/scan_compression.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/pipeline/team_radio.hpp"

namespace cosmo::pipeline {

namespace {
std::vector<char> keysOf(const std::map<char, Trajectory>& m) {
  std::vector<char> r;
  for (const auto& [k, v] : m) r.push_back(k);
  return r;
}
}  // namespace

TeamRun::TeamRun(std::string dataset_name, std::map<char, Trajectory> references, const TeamRunParams& params,
                 std::uint64_t radio_seed, StampNs time_origin)
    : params_(params),
      radio_(params.radio, keysOf(references), radio_seed),
      schedule_(keysOf(references), true),
      recorder_(std::move(dataset_name), keysOf(references), params.noise, params.outlier_rule),
      payloads_(params.radio.size_model == comm::RadioParams::SizeModel::RealCompressed),
      origin_(time_origin) {
  // One feature cache for the team: a delivered scan is the sender's own object, so its features are computed
  // once, not once per robot that registers against it (same results).
  recorder_.setMetadata(params.metadata);
  radio_.setTimeOrigin(time_origin);
  auto features = std::make_shared<frontend::FeatureCache>(
      params.frontend.spill_keyframes ? std::make_shared<frontend::SpillFile>(params.frontend.spill_dir) : nullptr);
  if (params.registration_threads > 0) pool_ = std::make_shared<frontend::RegistrationPool>(params.registration_threads);
  for (auto& [robot, ref] : references) {
    frontend::FrontendSetup setup;
    setup.params = params.frontend;
    setup.reference = std::move(ref);
    setup.features = features;
    setup.pool = pool_;
    frontends_[robot] = std::make_unique<frontend::RobotFrontend>(robot, std::move(setup));
  }
}

std::vector<char> TeamRun::robots() const { return radio_.robots(); }

const frontend::RobotFrontend& TeamRun::frontend(char robot) const {
  auto it = frontends_.find(robot);
  if (it == frontends_.end()) throw std::invalid_argument(std::string("team run: unknown robot '") + robot + "'");
  return *it->second;
}

void TeamRun::record(const frontend::LoopClosureAttempt& a) {
  if (on_loop_closure) on_loop_closure(a);
  if (a.inter()) {
    ++(a.accepted ? counts_.inter_accepted : counts_.inter_rejected);
  } else {
    ++(a.accepted ? counts_.intra_accepted : counts_.intra_rejected);
  }
  if (!a.accepted) return;
  dataset::LoopClosureMeasurement m;
  m.owner = a.owner;
  m.computed_at = a.computed_at;
  m.key1 = jrl::symbol(a.robot1, a.index1);
  m.key2 = jrl::symbol(a.robot2, a.index2);
  m.measurement = a.measurement;
  try {
    recorder_.addLoopClosure(m);
  } catch (const std::exception& e) {
    ++counts_.recorder_rejected;
    warnings_.push_back(std::string("loop closure refused by the recorder: ") + e.what());
  }
}

void TeamRun::advanceRadioTo(StampNs t) {
  const auto state = [this](char robot, StampNs step_stamp) {
    const frontend::RobotFrontend& fe = *frontends_.at(robot);
    RadioRobotState s;
    s.on = fe.scansProcessed() > 0;
    s.position = radioPosition(fe.reference(), step_stamp, fe.lastOdomPose().translation());
    return s;
  };
  const auto deliver = [this](StampNs step_stamp, const comm::Transfer& tr) {
    if (tr.outcome != comm::Transfer::Outcome::Delivered) {
      ++counts_.transfers_timed_out;
      return;
    }
    ++counts_.transfers_delivered;
    frontend::RobotFrontend& receiver = *frontends_.at(tr.receiver);
    frontend::Step step;
    if (payloads_.compresses()) {  // the real size model: the decompressed payload
      const std::shared_ptr<const Scan> scan = payloads_.deliver(tr.sender, tr.keyframe);
      if (!scan) return;
      step = receiver.add(frontend::TeammateScan::shared(tr.sender, tr.keyframe, scan, step_stamp));
    } else {  // the paper's: the sender's own kept scan (one copy, on disk, its features shared)
      std::shared_ptr<const frontend::KeptScan> kept = frontends_.at(tr.sender)->keptScan(tr.keyframe);
      if (!kept) return;
      step = receiver.add(frontend::TeammateScan::keptBySender(tr.sender, tr.keyframe, std::move(kept), step_stamp));
    }
    take(receiver, std::move(step));
  };
  advanceRadio(radio_, origin_, t, state, deliver);
  schedule_.radioStepped(nextRadioStepStamp(radio_, origin_), {});
}

void TeamRun::beforeScan(char robot, StampNs stamp) {
  if (schedule_.beforeScan(robot, stamp).step_radio) advanceRadioTo(stamp);
}

frontend::RobotFrontend& TeamRun::frontendFor(char robot) {
  return const_cast<frontend::RobotFrontend&>(frontend(robot));  // the front-ends themselves are not const
}

void TeamRun::add(char robot, const frontend::OwnScan& scan) {
  frontend::RobotFrontend& fe = frontendFor(robot);
  beforeScan(robot, scan.stamp);
  ++counts_.scans;
  take(fe, fe.add(scan));
}

void TeamRun::take(const frontend::RobotFrontend& fe, frontend::Step step) {
  const char robot = fe.robot();
  if (step.keyframe) {
    const frontend::KeyframeRecord& kf = *step.keyframe;
    ++counts_.keyframes;
    pending_.push_back(PendingRecord{kf, {}});
    const std::shared_ptr<const Scan> kf_scan = fe.keyframeScan(kf.index);
    comm::PayloadStore::Sizes sizes{comm::rawPayloadBytes(*kf_scan), comm::rawPayloadBytes(*kf_scan)};
    if (payloads_.compresses()) sizes = payloads_.offer(robot, kf.index, kf_scan);
    radio_.offerKeyframe(robot, kf.index, sizes.payload, sizes.raw);
  }
  for (auto& p : step.closures) {
    pending_.push_back(PendingRecord{std::nullopt, std::move(p)});
    ++pending_loop_closures_;
  }
  flush(false);
}

void TeamRun::recordKeyframe(const frontend::KeyframeRecord& kf) {
  try {
    recorder_.addKeyframe(kf.robot, kf.index, kf.stamp, kf.relative, kf.reference);
  } catch (const std::exception& e) {
    ++counts_.recorder_rejected;
    warnings_.push_back(std::string("keyframe refused by the recorder: ") + e.what());
  }
}

void TeamRun::flush(bool wait) {
  while (!pending_.empty()) {
    PendingRecord& front = pending_.front();
    if (front.keyframe) {
      recordKeyframe(*front.keyframe);
    } else {
      if (!wait && pending_loop_closures_ <= kMaxPending && !front.loop_closure.ready()) return;
      record(frontendFor(front.loop_closure.attempt.owner).complete(front.loop_closure));
      --pending_loop_closures_;
    }
    pending_.pop_front();
  }
}

void TeamRun::drain() { flush(true); }

void TeamRun::finish(StampNs end) {
  advanceRadioTo(end);
  drain();
}

}  // namespace cosmo::pipeline
