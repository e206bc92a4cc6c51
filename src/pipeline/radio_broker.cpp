#include "cosmo/pipeline/radio_broker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cosmo/comm/radio_status.hpp"
#include "cosmo/sequence/seed_streams.hpp"
#include "cosmo/pipeline/team_radio.hpp"

namespace cosmo::pipeline {

RadioBroker::RadioBroker(const comm::RadioParams& params, std::vector<char> robots, std::uint64_t seed, bool lockstep,
                         bool compress, std::uint32_t xz_preset)
    : lockstep_(lockstep),
      radio_(std::make_unique<comm::RadioSimulator>(params, std::move(robots), seed)),
      payloads_(compress, xz_preset) {}

void RadioBroker::offer(char robot, std::uint32_t index, comm::PayloadStore::Payload payload) {
  const comm::PayloadStore::Sizes sizes = payloads_.store(robot, index, std::move(payload));
  radio_->offerKeyframe(robot, index, sizes.payload, sizes.raw);
  std::uint32_t& next = next_index_[robot];
  next = std::max(next, index + 1);
  if (lockstep_ && !started()) early_offers_.push_back({robot, index, sizes});
  steps_.offerArrived(robot);
}

bool RadioBroker::positionReported(char robot, const Eigen::Vector3d& position) {
  if (lockstep_) {
    last_position_[robot] = position;
    return true;
  }
  if (!position.allFinite()) return false;
  radio_->setRobotState(robot, position, true);
  return true;
}

std::vector<char> RadioBroker::setSequence(StampNs start, std::uint64_t sequence_seed,
                                           const std::vector<char>& sequence_robots) {
  sequence_ = {start, sequence_seed};
  std::vector<char> missing;
  for (char r : radio_->robots())
    if (std::find(sequence_robots.begin(), sequence_robots.end(), r) == sequence_robots.end()) {
      missing.push_back(r);
      references_[r] = Trajectory{};
    }
  return missing;
}

void RadioBroker::setReference(char robot, Trajectory reference) { references_[robot] = std::move(reference); }

bool RadioBroker::readyToStart() const {
  if (started() || !sequence_) return false;
  for (char r : radio_->robots())
    if (!references_.count(r)) return false;
  return true;
}

std::uint64_t RadioBroker::start() {
  if (!readyToStart()) throw std::logic_error("radio broker: started before the sequence and references arrived");
  origin_ = radioGridOrigin(sequence_->first, radio_->params().step);
  const std::uint64_t seed = sequence::deriveSeed(sequence_->second, "radio");
  radio_ = std::make_unique<comm::RadioSimulator>(radio_->params(), radio_->robots(), seed);
  radio_->setTimeOrigin(origin_);
  for (const EarlyOffer& o : early_offers_) radio_->offerKeyframe(o.robot, o.index, o.sizes.payload, o.sizes.raw);
  early_offers_.clear();
  steps_.start();
  return seed;
}

void RadioBroker::runReadySteps(const DeliveryFn& on_delivery, const StepDoneFn& on_done) {
  while (const std::optional<QueuedRadioStep> request = steps_.popReady()) on_done(runStep(*request, on_delivery));
}

RadioBroker::StepDone RadioBroker::runStep(const QueuedRadioStep& request, const DeliveryFn& on_delivery) {
  StampNs last_step = 0;
  const auto state = [&](char r, StampNs step_stamp) {
    last_step = step_stamp;
    RadioRobotState s;
    s.on = request.on(r);
    const auto reference = references_.find(r);
    const auto last = last_position_.find(r);
    s.position = radioPosition(reference == references_.end() ? Trajectory{} : reference->second, step_stamp,
                               last == last_position_.end() ? Eigen::Vector3d::Zero() : last->second);
    return s;
  };
  const auto on_transfer = [&](StampNs step_stamp, const comm::Transfer& x) {
    deliver(x, toSeconds(step_stamp - origin_), step_stamp, on_delivery);
  };
  StepDone done;
  done.seq = request.seq;
  done.steps = advanceRadio(*radio_, origin_, request.order.through, state, on_transfer);
  if (done.steps > 0) last_step_ = last_step;
  done.last_step = last_step_;
  done.next_step = nextRadioStepStamp(*radio_, origin_);
  for (char r : radio_->robots()) done.delivered[r] = delivered_[r];
  return done;
}

RadioBroker::StepBatch RadioBroker::stepRealTime(double now, const DeliveryFn& on_delivery) {
  StepBatch batch;
  const double dt = radio_->params().step;
  if (!grid_started_ || now - radio_->nextStepTime() > 3600.0) {
    batch.grid_restarted = grid_started_;
    radio_->setStartTime(std::ceil(now / dt - 1e-9) * dt);
    if (!grid_started_) radio_->setTraceOrigin(radio_->nextStepTime());  // a trace's time 0: the first step
    grid_started_ = true;
  } else if (radio_->nextStepTime() - now > 1.0) {
    batch.time_went_back = true;
  }
  while (radio_->nextStepTime() <= now + 1e-9) {
    batch.last_time = radio_->nextStepTime();
    for (const comm::Transfer& x : radio_->step(batch.last_time)) deliver(x, batch.last_time, 0, on_delivery);
    for (const auto& [pair, c] : lastStepLinks(*radio_)) batch.links[pair] = c;
    ++batch.steps;
  }
  return batch;
}

void RadioBroker::deliver(const comm::Transfer& transfer, double step_time, StampNs step_stamp,
                          const DeliveryFn& on_delivery) {
  Delivery d{transfer, step_time, step_stamp, nullptr, {}};
  if (d.delivered()) {
    try {
      d.scan = payloads_.deliver(transfer.sender, transfer.keyframe);
    } catch (const std::exception& e) { d.error = e.what(); }
  }
  if (on_delivery(d) && d.delivered()) ++delivered_[transfer.receiver];
}

}  // namespace cosmo::pipeline
