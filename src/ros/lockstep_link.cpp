#include "cosmo/ros/lockstep_link.hpp"

#include <algorithm>
#include <string>

#include "cosmo/ros/lockstep_msgs.hpp"
#include "cosmo/ros/node_main.hpp"

namespace cosmo::ros_glue {

LockstepLink::LockstepLink(ros::NodeHandle& nh, const std::vector<char>& robots, double ack_timeout)
    : ack_timeout_(ack_timeout), schedule_(robots, false) {
  step_pub_ = nh.advertise<cosmo::RadioStepRequest>("/comm/step_request", 10);
  for (char r : robots)
    ack_subs_.push_back(nh.subscribe<cosmo::FrontendAck>(
        std::string("/") + r + "/ack", 1000, [this, r](const cosmo::FrontendAck::ConstPtr& m) { onAck(r, *m); }));
  step_done_sub_ = nh.subscribe<cosmo::RadioStepDone>(
      "/comm/step_done", 100, [this](const cosmo::RadioStepDone::ConstPtr& m) { onStepDone(*m); });
  recorder_sub_ = nh.subscribe<cosmo::RecorderProgress>(
      "/recorder/progress", 10, [this](const cosmo::RecorderProgress::ConstPtr& m) { onRecorder(*m); });
}

bool LockstepLink::connect(const ros::WallTime& deadline, bool wait_for_broker) {
  for (auto& sub : ack_subs_) waitUntil([&] { return sub.getNumPublishers() > 0; }, deadline);
  if (wait_for_broker) {
    const auto broker = [&] { return step_pub_.getNumSubscribers() > 0 && step_done_sub_.getNumPublishers() > 0; };
    waitUntil(broker, deadline);
    use_broker_ = broker();
    if (!use_broker_) ROS_WARN("player: lockstep without a lockstep comm_broker (no /comm/step_request subscriber)");
  }
  std::lock_guard<std::mutex> lock(mutex_);
  schedule_.useRadio(use_broker_);
  return use_broker_;
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
  waitFor("recorder intake", [&] { return schedule_.recorderComplete(); });
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
  for (std::size_t i = 0; i < m.robots.size() && i < m.keyframes.size() && i < m.loop_closures.size(); ++i)
    schedule_.recorderReported(m.robots[i], m.keyframes[i], m.loop_closures[i]);
}

bool LockstepLink::waitFor(const char* what, const std::function<bool()>& done) {
  const auto locked = [&] {
    std::lock_guard<std::mutex> lock(mutex_);
    return done();
  };
  if (waitUntil(locked, wallDeadline(ack_timeout_), 0.0005)) return true;
  if (ros::ok()) ROS_WARN("player: no %s within %.0f s; continuing", what, ack_timeout_);
  return false;
}

void LockstepLink::waitForScans() {
  if (waitFor("front-end ack", [&] { return schedule_.scansProcessed(); })) return;
  std::lock_guard<std::mutex> lock(mutex_);
  std::string behind;
  for (char r : schedule_.robotsBehind()) behind += r;
  ROS_WARN("player: front-ends %s did not acknowledge their last scan; going on without", behind.c_str());
  schedule_.stopWaitingForScans();
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
  if (!waitFor("comm_broker step", [&] { return step_done_seq_ >= seq; })) return;
  waitFor("delivered scans processed", [&] { return schedule_.deliveriesProcessed(); });
}

}  // namespace cosmo::ros_glue
