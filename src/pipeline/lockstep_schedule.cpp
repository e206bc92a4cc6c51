#include "cosmo/pipeline/lockstep_schedule.hpp"

#include <stdexcept>
#include <string>

namespace cosmo::pipeline {

LockstepSchedule::LockstepSchedule(std::vector<char> robots, bool with_radio)
    : robots_(std::move(robots)), with_radio_(with_radio) {
  for (char r : robots_) progress_[r];
}

LockstepSchedule::BeforeScan LockstepSchedule::beforeScan(char robot, StampNs stamp) const {
  BeforeScan b;
  b.step_radio = with_radio_ && (!radio_stepped_ || stamp >= next_step_);
  b.wait_for_scans = b.step_radio || handed_over_.count(robot) > 0;
  return b;
}

void LockstepSchedule::scanHandedOver(char robot, StampNs stamp) {
  const auto it = progress_.find(robot);
  if (it != progress_.end() && it->second.last_scan >= stamp) return;  // its report came first
  handed_over_[robot] = stamp;
}

const FrontendProgress& LockstepSchedule::progress(char robot) const {
  const auto it = progress_.find(robot);
  if (it == progress_.end())
    throw std::invalid_argument(std::string("lockstep schedule: unknown robot '") + robot + "'");
  return it->second;
}

void LockstepSchedule::frontendReported(char robot, const FrontendProgress& p) {
  const auto it = progress_.find(robot);
  if (it == progress_.end()) return;  // not a robot of the team
  FrontendProgress& mine = it->second;
  const StampNs last = std::max(mine.last_scan, p.last_scan);
  mine = p;
  mine.last_scan = last;
  const auto h = handed_over_.find(robot);
  if (h != handed_over_.end() && last >= h->second) handed_over_.erase(h);
}

void LockstepSchedule::radioStepped(StampNs next_step, const std::map<char, std::uint32_t>& delivered) {
  radio_stepped_ = true;
  next_step_ = next_step;
  for (const auto& [r, n] : delivered) delivered_[r] = n;
}

void LockstepSchedule::recorderReported(char robot, std::uint64_t acked) {
  recorder_reported_ = true;
  recorded_[robot] = acked;
}

bool LockstepSchedule::scansProcessed() const { return handed_over_.empty(); }

std::vector<char> LockstepSchedule::robotsBehind() const {
  std::vector<char> behind;
  for (const auto& [r, stamp] : handed_over_) behind.push_back(r);
  return behind;
}

bool LockstepSchedule::deliveriesProcessed() const {
  for (const auto& [r, n] : delivered_) {
    const auto it = progress_.find(r);
    if (n > 0 && (it == progress_.end() || it->second.received < n)) return false;
  }
  return true;
}

bool LockstepSchedule::recorderComplete() const { return !recorder_reported_ || robotsNotRecorded().empty(); }

std::vector<char> LockstepSchedule::robotsNotRecorded() const {
  std::vector<char> behind;
  for (const auto& [r, p] : progress_) {
    const auto it = recorded_.find(r);
    if ((it == recorded_.end() ? 0 : it->second) < p.seq) behind.push_back(r);
  }
  return behind;
}

RadioStepOrder LockstepSchedule::radioStepOrder(StampNs through) const {
  RadioStepOrder order;
  order.through = through;
  for (char r : robots_) {
    const FrontendProgress& p = progress_.at(r);
    order.robots.push_back(r);
    order.on.push_back(p.scans > 0);
    order.keyframes.push_back(p.keyframes);
  }
  return order;
}

}  // namespace cosmo::pipeline
