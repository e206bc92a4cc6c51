#include "cosmo/ros/lockstep_link.hpp"

#include <algorithm>
#include <string>

#include "cosmo/ros/lockstep_msgs.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/recorder_msgs.hpp"

namespace cosmo::ros_glue {

namespace {
constexpr double kNoticePeriod = 10.0;  // s between "still waiting" messages

std::string robotList(const std::vector<char>& robots) {
  std::string s;
  for (char r : robots) s += (s.empty() ? "" : ", ") + std::string(1, r);
  return s;
}
}  // namespace

LockstepLink::LockstepLink(ros::NodeHandle& nh, const std::vector<char>& robots, Peers peers)
    : peers_(std::move(peers)), schedule_(robots, false) {
  if (!peers_.recorder.empty()) schedule_.expectRecorder();
  step_pub_ = nh.advertise<cosmo::RadioStepRequest>("/comm/step_request", 10);
  for (char r : robots) {
    ack_index_[r] = ack_subs_.size();
    ack_subs_.push_back(nh.subscribe<cosmo::FrontendAck>(
        std::string("/") + r + "/ack", 1000, [this, r](const cosmo::FrontendAck::ConstPtr& m) { onAck(r, *m); }));
  }
  step_done_sub_ = nh.subscribe<cosmo::RadioStepDone>(
      "/comm/step_done", 100, [this](const cosmo::RadioStepDone::ConstPtr& m) { onStepDone(*m); });
  recorder_sub_ = nh.subscribe<cosmo::RecorderProgress>(
      "/recorder/progress", 10, [this](const cosmo::RecorderProgress::ConstPtr& m) { onRecorder(*m); });
}

bool LockstepLink::frontendLinked(char robot) const {
  const auto it = ack_index_.find(robot);
  return it != ack_index_.end() && ack_subs_[it->second].getNumPublishers() > 0;
}

bool LockstepLink::brokerLinked() const {
  return step_pub_.getNumSubscribers() > 0 && step_done_sub_.getNumPublishers() > 0;
}

void LockstepLink::useBroker(bool use) {
  std::lock_guard<std::mutex> lock(mutex_);
  use_broker_ = use;
  schedule_.useRadio(use);
  if (!use) ROS_WARN("player: lockstep without a lockstep comm_broker: no radio");
}

void LockstepLink::beforeScan(char robot, StampNs stamp) {
  pipeline::LockstepSchedule::BeforeScan before;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    before = schedule_.beforeScan(robot, stamp);
  }
  if (before.wait_for_scans) waitForScans();
  if (before.step_radio) stepRadio(stamp);
}

void LockstepLink::scanHandedOver(char robot, StampNs stamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  schedule_.scanHandedOver(robot, stamp);
}

void LockstepLink::finish(StampNs end) {
  waitForScans();
  stepRadio(end);
  waitFor(
      [&] {
        return "the recorder to hold every measurement of robots " + robotList(schedule_.robotsNotRecorded()) +
               describePeer(peers_.recorder);
      },
      [&] { return schedule_.recorderComplete(); });
}

void LockstepLink::onAck(char robot, const cosmo::FrontendAck& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  schedule_.frontendReported(robot, frontendProgressFromMsg(m));
}

void LockstepLink::onStepDone(const cosmo::RadioStepDone& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  schedule_.radioStepped(m.next_stamp.toNSec(), deliveredFromMsg(m));
  step_done_seq_ = std::max(step_done_seq_, m.seq);
}

void LockstepLink::onRecorder(const cosmo::RecorderProgress& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (char r : m.robots) schedule_.recorderReported(r, recorderAcked(m, r));
}

bool LockstepLink::waitFor(const std::function<std::string()>& what, const std::function<bool()>& done) {
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime next_notice = start + ros::WallDuration(kNoticePeriod);
  while (ros::ok()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (done()) return true;
    }
    if (peers_.monitor)
      if (const std::optional<std::string> stop = peers_.monitor->stopReason()) throw RunStopped(*stop);
    const ros::WallTime now = ros::WallTime::now();
    if (now >= next_notice) {
      std::string waited;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        waited = what();
      }
      ROS_INFO("player: still waiting (%.0f s) for %s", (now - start).toSec(), waited.c_str());
      next_notice = now + ros::WallDuration(kNoticePeriod);
    }
    ros::WallDuration(0.0005).sleep();
  }
  return false;
}

std::string LockstepLink::describePeer(const std::string& node) const {
  if (!peers_.monitor || node.empty()) return "";
  try {
    return "; " + peers_.monitor->describe(node);
  } catch (const std::exception&) { return ""; }
}

void LockstepLink::waitForScans() {
  waitFor(
      [&] {
        std::string peers;
        for (char r : schedule_.robotsBehind())
          if (const auto it = peers_.frontends.find(r); it != peers_.frontends.end()) peers += describePeer(it->second);
        return "the acks of robots " + robotList(schedule_.robotsBehind()) + " for their last scan" + peers;
      },
      [&] { return schedule_.scansProcessed(); });
}

// The broker runs every radio step <= t once the keyframes offered so far reached it; the scans it delivered are
// processed by their receivers before anything else happens.
void LockstepLink::stepRadio(StampNs t) {
  if (!use_broker_) return;
  pipeline::RadioStepOrder order;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    order = schedule_.radioStepOrder(t);
  }
  const std::uint32_t seq = ++step_seq_;
  step_pub_.publish(radioStepRequestMsg(seq, t, order));
  if (!waitFor([&] { return "the comm_broker's radio step " + std::to_string(seq) + describePeer(peers_.broker); },
               [&] { return step_done_seq_ >= seq; }))
    return;
  waitFor([&] { return "the processing of the scans the radio delivered"; },
          [&] { return schedule_.deliveriesProcessed(); });
}

}  // namespace cosmo::ros_glue
