#include "cosmo/ros/recorder_link.hpp"

#include <nlohmann/json.hpp>

#include "cosmo/ros/recorder_msgs.hpp"

namespace cosmo::ros_glue {

namespace {
double now() { return ros::WallTime::now().toSec(); }
constexpr double kBrokerWait = 2.0;  // s a restart waits for the comm_broker's offers (/comm/offered, latched)
}  // namespace

RecorderLink::RecorderLink(ros::NodeHandle& nh, char robot, bool may_continue, double recorder_wait,
                           double resend_after)
    : robot_(robot), recorder_wait_(recorder_wait), start_(ros::WallTime::now()), outbox_(resend_after) {
  if (!may_continue) decided_ = continuation_;
  kf_pub_ = nh.advertise<cosmo::RecorderKeyframe>("keyframes_meas", 1000);
  lc_pub_ = nh.advertise<cosmo::RecorderLoopClosure>("loop_closures", 1000);
  progress_sub_ = nh.subscribe<cosmo::RecorderProgress>(
      "/recorder/progress", 10, [this](const cosmo::RecorderProgress::ConstPtr& m) { onProgress(*m); });
  if (may_continue)
    offered_sub_ = nh.subscribe<std_msgs::String>("/comm/offered", 1,
                                                  [this](const std_msgs::String::ConstPtr& m) { onBrokerOffers(*m); });
  resend_timer_ = nh.createWallTimer(ros::WallDuration(0.25), [this](const ros::WallTimerEvent&) { resend(); });
}

bool RecorderLink::decided() {
  if (decided_) return true;
  const double waited = (ros::WallTime::now() - start_).toSec();
  if (progress_ && !progress_->session.empty()) {
    const live::RecorderHolding held = recorderHolding(*progress_, robot_);
    const bool holds = held.highest_seq > 0 || held.next_index > 0;
    if (holds && !broker_next_index_ && waited < kBrokerWait) return false;
    continuation_ = live::continueAfter(held, broker_next_index_);
  } else if (waited < recorder_wait_) {
    return false;
  } else {
    ROS_WARN("frontend %c: no recorder answered within %.0f s (/recorder/progress): starting afresh; should this "
             "front-end be a restart, its keyframe indices may repeat its predecessor's",
             robot_, recorder_wait_);
  }
  decided_ = continuation_;
  outbox_.numberFrom(continuation_.first_seq);
  bridge_pending_ = continuation_.bridge_from.has_value();
  ROS_INFO("frontend %c: %s", robot_, continuation_.describe().c_str());
  return true;
}

void RecorderLink::onProgress(const cosmo::RecorderProgress& m) {
  progress_ = m;
  if (m.session.empty()) return;
  outbox_.acknowledged(m.session, recorderAcked(m, robot_));
  resend();
}

void RecorderLink::onBrokerOffers(const std_msgs::String& m) {
  try {
    broker_next_index_ = nlohmann::json::parse(m.data).value(std::string(1, robot_), std::uint32_t{0});
  } catch (const std::exception&) {}
}

void RecorderLink::send(cosmo::RecorderKeyframe keyframe) {
  if (bridge_pending_) {
    keyframe.bridge = true;
    keyframe.bridge_from = *continuation_.bridge_from;
    bridge_pending_ = false;
  }
  keyframe.seq = outbox_.lastSeq() + 1;  // the number add() gives it
  Message m = std::move(keyframe);
  outbox_.add(m, now());
  publish(m);
}

void RecorderLink::send(cosmo::RecorderLoopClosure closure) {
  closure.seq = outbox_.lastSeq() + 1;
  Message m = std::move(closure);
  outbox_.add(m, now());
  publish(m);
}

void RecorderLink::publish(const Message& m) {
  if (const auto* k = std::get_if<cosmo::RecorderKeyframe>(&m))
    kf_pub_.publish(*k);
  else
    lc_pub_.publish(std::get<cosmo::RecorderLoopClosure>(m));
}

void RecorderLink::resend() {
  for (const auto& [seq, m] : outbox_.due(now())) publish(*m);
}

}  // namespace cosmo::ros_glue
