#include "cosmo/comm/radio_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cosmo/comm/radio_random.hpp"

namespace cosmo::comm {

namespace {
std::string robotName(char id) { return std::string("'") + id + "'"; }

const RadioParams& validated(const RadioParams& p) {
  p.validate();
  return p;
}
}  // namespace

std::string toString(Transfer::Outcome outcome) {
  return outcome == Transfer::Outcome::Delivered ? "delivered" : "timed_out";
}

std::string toString(Transfer::Link link) {
  return link == Transfer::Link::Distance ? "distance" : link == Transfer::Link::Trace ? "trace" : "mixed";
}

RadioSimulator::RadioSimulator(const RadioParams& p, std::vector<char> robots, std::uint64_t seed)
    : params_(validated(p)), seed_(seed), rng_(seed), link_(p), connectivity_(robots, p.step) {
  std::sort(robots.begin(), robots.end());
  robots.erase(std::unique(robots.begin(), robots.end()), robots.end());
  if (robots.empty()) throw std::invalid_argument("RadioSimulator: the team has no robots");
  robot_ids_ = robots;
  for (char r : robot_ids_) robots_[r] = Robot{};
  if (params_.trace) params_.trace->checkTeam(robot_ids_);
}

RadioSimulator::Robot& RadioSimulator::robot(char id, const char* what) {
  auto it = robots_.find(id);
  if (it == robots_.end())
    throw std::invalid_argument(std::string("RadioSimulator::") + what + ": unknown robot " + robotName(id));
  return it->second;
}

const RadioSimulator::Robot& RadioSimulator::robot(char id, const char* what) const {
  auto it = robots_.find(id);
  if (it == robots_.end())
    throw std::invalid_argument(std::string("RadioSimulator::") + what + ": unknown robot " + robotName(id));
  return it->second;
}

void RadioSimulator::setRobotState(char id, const Eigen::Vector3d& position, bool on) {
  Robot& r = robot(id, "setRobotState");
  if (!position.allFinite())
    throw std::invalid_argument("RadioSimulator::setRobotState: non-finite position of robot " + robotName(id));
  r.position = position;
  r.on = on;
}

void RadioSimulator::offerKeyframe(char id, std::size_t keyframe, std::size_t payload_bytes, std::size_t raw_bytes) {
  Robot& r = robot(id, "offerKeyframe");
  Offer offer;
  if (params_.size_model == RadioParams::SizeModel::RealCompressed) {
    offer.payload_bytes = payload_bytes;
  } else {
    const double s =
        raw_bytes > 0 ? static_cast<double>(raw_bytes) : static_cast<double>(payload_bytes) / params_.size_factor_mean;
    std::mt19937_64 size_rng(radio_random::mixSeed(seed_, static_cast<unsigned char>(id), keyframe));
    const double f =
        std::max(0.01, radio_random::normal(size_rng, params_.size_factor_mean, params_.size_factor_stddev));
    offer.payload_bytes = static_cast<std::size_t>(std::llround(f * s));
  }
  if (r.offers.count(keyframe) == 0) ++stats_.keyframes_offered;
  r.offers[keyframe] = offer;
}

void RadioSimulator::setStartTime(double t) {
  start_time_ = t;
  next_index_ = 0;
}

bool RadioSimulator::wasDelivered(char sender, char receiver, std::size_t keyframe) const {
  const Robot& s = robot(sender, "wasDelivered");
  auto it = s.delivered_to.find(receiver);
  return it != s.delivered_to.end() && it->second.count(keyframe) > 0;
}

std::size_t RadioSimulator::undeliveredCount(char sender, char receiver) const {
  const Robot& s = robot(sender, "undeliveredCount");
  auto it = s.delivered_to.find(receiver);
  return s.offers.size() - (it == s.delivered_to.end() ? 0 : it->second.size());
}

std::size_t RadioSimulator::payloadSize(char id, std::size_t keyframe) const {
  const Robot& r = robot(id, "payloadSize");
  auto it = r.offers.find(keyframe);
  return it == r.offers.end() ? 0 : it->second.payload_bytes;
}

bool RadioSimulator::isOn(char id) const { return robot(id, "isOn").on; }
Eigen::Vector3d RadioSimulator::position(char id) const { return robot(id, "position").position; }

std::size_t RadioSimulator::pickKeyframe(const Robot& sender, char receiver) {
  const auto it = sender.delivered_to.find(receiver);
  const std::set<std::size_t>* done = it == sender.delivered_to.end() ? nullptr : &it->second;
  const std::size_t n = sender.offers.size() - (done ? done->size() : 0);
  std::size_t k = radio_random::index(rng_, n);
  for (const auto& [kf, offer] : sender.offers) {
    if (done && done->count(kf)) continue;
    if (k == 0) return kf;
    --k;
  }
  throw std::logic_error("RadioSimulator::pickKeyframe: no undelivered keyframe");
}

std::vector<Transfer> RadioSimulator::step(double t) {
  if (!std::isfinite(t)) throw std::invalid_argument("RadioSimulator::step: non-finite time");
  if (stepped_ && !(t > last_time_))
    throw std::invalid_argument("RadioSimulator::step: time " + std::to_string(t) +
                                " s is not after the previous step " + std::to_string(last_time_) + " s");
  if (std::abs(t - nextStepTime()) > 1e-6 * params_.step) setStartTime(t);
  ++next_index_;
  stepped_ = true;
  last_time_ = t;
  ++stats_.steps;

  initializeNewCommunications(t);
  updateActiveCommunications(t);
  last_step_ = active_;
  std::vector<Transfer> ended = terminateCommunications(t);
  for (const Transfer& x : ended) connectivity_.addTransfer(x);
  connectivity_.endStep(
      t,
      [&](char a, char b) {
        const Robot& ra = robots_.at(a);
        const Robot& rb = robots_.at(b);
        return link_.connected(a, b, t, (ra.position - rb.position).norm(), ra.on && rb.on);
      },
      [&](char r) { return robots_.at(r).on; });
  return ended;
}

Connectivity RadioSimulator::connectivity() const {
  Connectivity c = connectivity_.result();
  c.time_origin_ns = time_origin_;
  c.d_init = params_.d_init;
  if (params_.trace) c.trace = params_.trace->source();
  return c;
}

LinkSample RadioSimulator::sampleLink(char a, char b, double t, double distance) {
  const LinkSample s = link_.sample(a, b, t, distance, radio_random::uniform01(rng_));
  if (params_.trace) ++(s.from_trace ? stats_.trace_samples : stats_.fallback_samples);
  return s;
}

void RadioSimulator::initializeNewCommunications(double t) {
  // Candidate pairs (sorted order), then a seeded random order so that no robot id is favoured.
  std::vector<std::pair<char, char>> candidates;
  for (std::size_t i = 0; i < robot_ids_.size(); ++i) {
    const Robot& a = robots_.at(robot_ids_[i]);
    if (!a.on || a.busy) continue;
    for (std::size_t j = i + 1; j < robot_ids_.size(); ++j) {
      const Robot& b = robots_.at(robot_ids_[j]);
      if (!b.on || b.busy) continue;
      if (!link_.inRange(robot_ids_[i], robot_ids_[j], t, (a.position - b.position).norm())) continue;
      if (undeliveredCount(robot_ids_[i], robot_ids_[j]) == 0 && undeliveredCount(robot_ids_[j], robot_ids_[i]) == 0)
        continue;
      candidates.emplace_back(robot_ids_[i], robot_ids_[j]);
    }
  }
  for (std::size_t i = candidates.size(); i > 1; --i)
    std::swap(candidates[i - 1], candidates[radio_random::index(rng_, i)]);

  for (const auto& [ia, ib] : candidates) {
    Robot& a = robots_.at(ia);
    Robot& b = robots_.at(ib);
    if (a.busy || b.busy) continue;
    const double d = (a.position - b.position).norm();
    ++stats_.init_attempts;
    const LinkSample link = sampleLink(ia, ib, t, d);
    if (!link.connected) continue;
    const std::size_t na = undeliveredCount(ia, ib), nb = undeliveredCount(ib, ia);
    const bool a_sends = na > nb || (na == nb && radio_random::bernoulli(rng_, 0.5));
    const char s = a_sends ? ia : ib, r = a_sends ? ib : ia;
    Robot& sender = a_sends ? a : b;
    ActiveCommunication c;
    c.sender = s;
    c.receiver = r;
    c.keyframe = pickKeyframe(sender, r);
    c.start = t;
    c.bytes = sender.offers.at(c.keyframe).payload_bytes;
    c.last_progress = t;
    c.distance = d;
    c.capacity_Bps = link.throughput_Bps;
    c.latency = link.latency;
    (link.from_trace ? c.used_trace : c.used_distance) = true;
    a.busy = b.busy = true;
    active_.push_back(c);
    new_this_step_.push_back(true);
    ++stats_.initiated;
  }
}

void RadioSimulator::updateActiveCommunications(double t) {
  // Interference over the set active now (same set for every communication of this step).
  const double r2 = params_.d_intf * params_.d_intf;
  std::vector<int> interference(active_.size(), 1);
  for (std::size_t i = 0; i < active_.size(); ++i) {
    const Eigen::Vector3d& a = robots_.at(active_[i].sender).position;
    const Eigen::Vector3d& b = robots_.at(active_[i].receiver).position;
    for (std::size_t j = 0; j < active_.size(); ++j) {
      if (i == j) continue;
      const Eigen::Vector3d& c = robots_.at(active_[j].sender).position;
      const Eigen::Vector3d& d = robots_.at(active_[j].receiver).position;
      if ((a - c).squaredNorm() <= r2 || (a - d).squaredNorm() <= r2 || (b - c).squaredNorm() <= r2 ||
          (b - d).squaredNorm() <= r2)
        ++interference[i];
    }
  }
  for (std::size_t i = 0; i < active_.size(); ++i) {
    ActiveCommunication& c = active_[i];
    const Robot& s = robots_.at(c.sender);
    const Robot& r = robots_.at(c.receiver);
    c.distance = (s.position - r.position).norm();
    c.interference = interference[i];
    bool connected = true;  // a new communication: the initialization sample is this step's sample
    if (!new_this_step_[i]) {
      connected = false;
      if (s.on && r.on) {
        const LinkSample link = sampleLink(c.sender, c.receiver, t, c.distance);
        (link.from_trace ? c.used_trace : c.used_distance) = true;
        connected = link.connected;
        if (connected) {
          c.capacity_Bps = link.throughput_Bps;
          c.latency = link.latency;
        }
      }
      ++stats_.link_samples;
      if (connected) ++stats_.link_successes;
    }
    const double rate = connected ? c.capacity_Bps / c.interference : 0.0;
    const double before = c.bytes_delivered;
    c.bytes_delivered = std::min(static_cast<double>(c.bytes), c.bytes_delivered + rate * params_.step);
    stats_.bytes_transmitted += c.bytes_delivered - before;
    connectivity_.addBytes(c.sender, c.receiver, c.bytes_delivered - before);
    c.throughput_Bps = rate;
    if (rate > 0.0) c.last_progress = t;
    new_this_step_[i] = false;
  }
}

void RadioSimulator::received(const Transfer& x) {
  ++stats_.delivered;
  stats_.bytes_delivered += static_cast<double>(x.bytes);
}

std::vector<Transfer> RadioSimulator::terminateCommunications(double t) {
  std::vector<Transfer> ended;
  std::vector<ActiveCommunication> keep;
  const double eps = 1e-9 * std::max(1.0, std::abs(t));
  std::vector<Transfer> flying;
  for (Transfer& x : in_flight_) {  // sent in earlier steps, arriving now
    if (x.received > t + eps) {
      flying.push_back(x);
      continue;
    }
    x.received = t;
    received(x);
    ended.push_back(x);
  }
  in_flight_ = std::move(flying);
  for (const ActiveCommunication& c : active_) {
    Transfer x;
    x.sender = c.sender;
    x.receiver = c.receiver;
    x.keyframe = c.keyframe;
    x.start = c.start;
    x.end = t;
    x.bytes = c.bytes;
    x.bytes_delivered = c.bytes_delivered;
    x.link =
        c.used_trace ? (c.used_distance ? Transfer::Link::Mixed : Transfer::Link::Trace) : Transfer::Link::Distance;
    if (c.bytes_delivered >= static_cast<double>(c.bytes)) {
      x.outcome = Transfer::Outcome::Delivered;
      robots_.at(c.sender).delivered_to[c.receiver].insert(c.keyframe);
      x.received = t + c.latency;
      if (c.latency > 0.0)
        in_flight_.push_back(x);  // reaches the receiver in a later step
      else
        received(x);
    } else {
      const double since = params_.timeout_mode == RadioParams::TimeoutMode::NoProgress ? c.last_progress : c.start;
      if (t - since < params_.timeout - eps) {
        keep.push_back(c);
        continue;
      }
      x.outcome = Transfer::Outcome::TimedOut;
      ++stats_.timed_out;
    }
    robots_.at(c.sender).busy = false;
    robots_.at(c.receiver).busy = false;
    if (x.outcome == Transfer::Outcome::TimedOut || c.latency <= 0.0) ended.push_back(x);
  }
  active_ = std::move(keep);
  new_this_step_.assign(active_.size(), false);
  stats_.in_flight = in_flight_.size();
  std::stable_sort(ended.begin(), ended.end(), [](const Transfer& a, const Transfer& b) {
    return a.sender != b.sender ? a.sender < b.sender : a.receiver < b.receiver;
  });
  log_.insert(log_.end(), ended.begin(), ended.end());
  return ended;
}

}  // namespace cosmo::comm
