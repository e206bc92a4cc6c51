#pragma once
// The player's side of the lockstep protocol on ROS: the team's event order (pipeline::LockstepSchedule, which
// TeamRun runs offline) driven through the nodes. It hears the front-ends' acks (/<r>/ack, cosmo/FrontendAck), the
// comm_broker's answers (/comm/step_done) and the recorder's intake (/recorder/progress), asks the broker for radio
// steps (/comm/step_request) and waits, polling on wall time (the callbacks run on a spinner thread), until what
// the schedule asks for happened. A wait has no time limit: it names what it waits for every 10 s, and it ends
// with RunStopped when the peer policy (PeerMonitor) says the run must stop (a peer died or never connected).
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <mutex>
#include <vector>

#include <ros/ros.h>

#include "cosmo/FrontendAck.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/common/time.hpp"
#include "cosmo/pipeline/lockstep_schedule.hpp"
#include "cosmo/ros/peer_probe.hpp"

namespace cosmo::ros_glue {

class LockstepLink {
 public:
  /// The peer policy that ends a wait, and the node names of the peers for the waits' messages.
  struct Peers {
    const PeerMonitor* monitor = nullptr;  ///< nullptr: waits end only with ROS
    std::map<char, std::string> frontends;
    std::string broker, recorder;
  };
  LockstepLink(ros::NodeHandle& nh, const std::vector<char>& robots, Peers peers);

  /// The topic connections with `robot`'s front-end (its acks) and with the broker (steps and their answers) are
  /// made: a message sent before its connection exists is lost, and the lockstep would wait for it.
  bool frontendLinked(char robot) const;
  bool brokerLinked() const;
  /// Whether a radio runs (a lockstep comm_broker is part of the run); set once every peer connected.
  void useBroker(bool use);
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
  /// Waits until `done` holds under the lock; `what` (called under the lock) says what is waited for. Throws
  /// RunStopped when the peer policy stops the run; false when ROS shuts down.
  bool waitFor(const std::function<std::string()>& what, const std::function<bool()>& done);
  /// "; <the peer's state>" for a message (empty when the peer is not watched).
  std::string describePeer(const std::string& node) const;
  void waitForScans();
  void stepRadio(StampNs t);

  Peers peers_;
  std::map<char, std::size_t> ack_index_;
  std::mutex mutex_;  ///< guards what the callbacks update: the schedule and step_done_seq_
  pipeline::LockstepSchedule schedule_;
  bool use_broker_ = false;
  std::uint32_t step_seq_ = 0, step_done_seq_ = 0;
  ros::Publisher step_pub_;
  std::vector<ros::Subscriber> ack_subs_;
  ros::Subscriber step_done_sub_, recorder_sub_;
};

}  // namespace cosmo::ros_glue
