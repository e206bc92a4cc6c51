#pragma once
// The player's side of the lockstep protocol on ROS: the team's event order (pipeline::LockstepSchedule, which
// TeamRun runs offline) driven through the nodes. It hears the front-ends' acks (/<r>/ack, cosmo/FrontendAck), the
// comm_broker's answers (/comm/step_done) and the recorder's intake (/recorder/progress), asks the broker for radio
// steps (/comm/step_request) and waits, polling on wall time (the callbacks run on a spinner thread), until what
// the schedule asks for happened; a wait gives up after `ack_timeout` with a warning (a silent node).
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include <ros/ros.h>

#include "cosmo/FrontendAck.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/common/time.hpp"
#include "cosmo/pipeline/lockstep_schedule.hpp"

namespace cosmo::ros_glue {

class LockstepLink {
 public:
  LockstepLink(ros::NodeHandle& nh, const std::vector<char>& robots, double ack_timeout);

  /// Waits until `deadline` for the front-ends' acks (and, with `wait_for_broker`, the broker) to connect: a
  /// message sent before its connection exists is lost, and the lockstep would wait for it. Returns whether a
  /// radio runs.
  bool connect(const ros::WallTime& deadline, bool wait_for_broker);
  /// What the event order runs before `robot`'s scan at `stamp`: the acks of the scans so far, the radio steps
  /// through `stamp` and the processing of what they delivered.
  void beforeScan(char robot, StampNs stamp);
  /// The scan was published.
  void scanHandedOver(char robot, StampNs stamp);
  /// The last acks, the radio through `end`, the recorder's intake complete.
  void finish(StampNs end);

 private:
  void onAck(char robot, const cosmo::FrontendAck& m);
  void onStepDone(const cosmo::RadioStepDone& m);
  void onRecorder(const cosmo::RecorderProgress& m);
  /// Waits until `done` holds under the lock, at most ack_timeout; false on a timeout (with a warning).
  bool waitFor(const char* what, const std::function<bool()>& done);
  void waitForScans();
  void stepRadio(StampNs t);

  double ack_timeout_;
  std::mutex mutex_;  ///< guards what the callbacks update: the schedule and step_done_seq_
  pipeline::LockstepSchedule schedule_;
  bool use_broker_ = false;
  std::uint32_t step_seq_ = 0, step_done_seq_ = 0;
  ros::Publisher step_pub_;
  std::vector<ros::Subscriber> ack_subs_;
  ros::Subscriber step_done_sub_, recorder_sub_;
};

}  // namespace cosmo::ros_glue
