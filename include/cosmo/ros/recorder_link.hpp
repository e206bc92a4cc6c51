#pragma once
// A front-end's side of the recorder protocol: its measurements (cosmo/RecorderKeyframe on keyframes_meas,
// cosmo/RecorderLoopClosure on loop_closures) numbered and kept in a live::Outbox until /recorder/progress
// acknowledges them, and sent again to a new recorder session or when not acknowledged within a second; and, for a
// front-end that may be a restart (real time), where its numbering continues (live::continueAfter): decided
// once the recorder's progress was heard (and the comm_broker's offers, /comm/offered, when the recorder holds
// something of the robot), or after `recorder_wait` s without a recorder (then afresh, with a warning).
// Everything runs on the node's own callback queue (ros::spin).
#include <optional>
#include <string>
#include <variant>

#include <ros/ros.h>
#include <std_msgs/String.h>

#include "cosmo/RecorderKeyframe.h"
#include "cosmo/RecorderLoopClosure.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/live/frontend_continuation.hpp"
#include "cosmo/live/outbox.hpp"

namespace cosmo::ros_glue {

class RecorderLink {
 public:
  /// `may_continue`: the front-end may be a restart (real time); else it starts afresh at once (lockstep).
  RecorderLink(ros::NodeHandle& nh, char robot, bool may_continue, double recorder_wait = 10.0,
               double resend_after = 1.0);

  /// Whether the numbering is decided (then continuation() holds).
  bool decided();
  const live::Continuation& continuation() const { return continuation_; }

  /// Numbers, keeps and publishes; the first keyframe of a restart is bridged.
  void send(cosmo::RecorderKeyframe keyframe);
  void send(cosmo::RecorderLoopClosure closure);
  /// The last number sent (0: none).
  std::uint64_t lastSeq() const { return outbox_.lastSeq(); }
  /// Measurements not acknowledged yet.
  std::size_t unacknowledged() const { return outbox_.size(); }

 private:
  using Message = std::variant<cosmo::RecorderKeyframe, cosmo::RecorderLoopClosure>;
  void onProgress(const cosmo::RecorderProgress& m);
  void onBrokerOffers(const std_msgs::String& m);
  void publish(const Message& m);
  void resend();

  char robot_;
  double recorder_wait_;
  ros::WallTime start_;
  std::optional<live::Continuation> decided_;
  live::Continuation continuation_;
  std::optional<cosmo::RecorderProgress> progress_;
  std::optional<std::uint32_t> broker_next_index_;
  bool bridge_pending_ = false;
  live::Outbox<Message> outbox_;
  ros::Publisher kf_pub_, lc_pub_;
  ros::Subscriber progress_sub_, offered_sub_;
  ros::WallTimer resend_timer_;
};

}  // namespace cosmo::ros_glue
