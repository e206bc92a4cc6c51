// comm_broker: the simulated radio between robots (RadioSimulator, the paper's Algorithm 1) on ROS time: keyframe
// scans offered, carried by the radio model, delivered (lockstep: in the player's radio steps, pipeline::RadioBroker).
// Topics, parameters and the lockstep protocol: docs/nodes.md.
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <visualization_msgs/MarkerArray.h>

#include <map>
#include <memory>
#include <mutex>

#include "cosmo/Keyframe.h"
#include "cosmo/comm/radio_status.hpp"
#include "cosmo/live/clock_skew.hpp"
#include "cosmo/pipeline/radio_broker.hpp"
#include "cosmo/ros/comm_broker_options.hpp"
#include "cosmo/ros/lockstep_msgs.hpp"
#include "cosmo/ros/markers.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {

using pipeline::RadioBroker;

class CommBroker {
 public:
  CommBroker(ros::NodeHandle& nh, ros_glue::CommBrokerOptions options)
      : o_(std::move(options)),
        radio_(o_.radio, o_.robots, static_cast<std::uint64_t>(o_.seed), o_.lockstep, o_.compress,
               static_cast<std::uint32_t>(o_.xz_preset)) {
    connectRobots(nh);
    if (!o_.lockstep)
      timer_ = nh.createWallTimer(ros::WallDuration(0.01), [this](const ros::WallTimerEvent&) { onTimer(); });
    if (o_.lockstep) connectLockstep(nh);
    ros_glue::logCommBrokerStart(o_);
  }

  ~CommBroker() { writeLog(); }

  void writeLog() {
    std::lock_guard<std::mutex> lock(mutex_);
    log_.write(radio());
  }

 private:
  const comm::RadioSimulator& radio() const { return radio_.radio(); }

  void connectRobots(ros::NodeHandle& nh) {
    for (char r : radio().robots()) {
      const std::string ns(1, r);
      keyframe_subs_.push_back(nh.subscribe<cosmo::Keyframe>(
          ns + "/keyframe_scans", 100, [this, r](const cosmo::Keyframe::ConstPtr& m) { onKeyframe(r, *m); }));
      pose_subs_.push_back(nh.subscribe<geometry_msgs::PoseStamped>(
          ns + "/reference_pose", 20, [this, r](const geometry_msgs::PoseStamped::ConstPtr& m) { onPose(r, *m); }));
      received_pubs_[r] = nh.advertise<cosmo::Keyframe>(ns + "/received_scans", 100);
    }
    links_pub_ = nh.advertise<visualization_msgs::MarkerArray>("comm/links", 2);
    stats_pub_ = nh.advertise<std_msgs::String>("comm/stats", 10);
    offered_pub_ = nh.advertise<std_msgs::String>("comm/offered", 1, true);
  }

  void connectLockstep(ros::NodeHandle& nh) {
    sequence_sub_ = nh.subscribe(ros_glue::kTeamSequenceTopic, 1, &CommBroker::onSequence, this);
    for (char r : radio().robots())
      trajectory_subs_.push_back(nh.subscribe<cosmo::ReferenceTrajectory>(
          ros_glue::referenceTrajectoryTopic(r), 1,
          [this, r](const cosmo::ReferenceTrajectory::ConstPtr& m) { onTrajectory(r, *m); }));
    step_done_pub_ = nh.advertise<cosmo::RadioStepDone>("comm/step_done", 100);
    step_request_sub_ = nh.subscribe("comm/step_request", 100, &CommBroker::onStepRequest, this);
  }

  /// Decode and pack (xz, outside the lock), then the offer to the radio.
  void onKeyframe(char r, const cosmo::Keyframe& m) {
    const std::string topic = std::string("/") + r + "/keyframe_scans";
    if (!m.robot.empty() && m.robot != std::string(1, r))
      ROS_WARN_THROTTLE(5.0, "comm_broker: %s: message says robot '%s'; using '%c'", topic.c_str(), m.robot.c_str(), r);
    comm::PayloadStore::Payload payload;
    try {
      auto scan = std::make_shared<Scan>();  // only x y z travel
      scan->points = ros_glue::fromPointCloud2(m.cloud, true, topic).points;
      payload = radio_.pack(std::move(scan));
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: dropping keyframe %u: %s", m.index, e.what());
      std::lock_guard<std::mutex> lock(mutex_);
      radio_.offerDropped(r);  // counted, so that a lockstep step waiting for it goes on
      runPendingSteps();
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!o_.lockstep && !ros::Time::isSimTime())  // live robots: their clocks against this one
      if (const auto skew = clock_skew_.observe(r, m.header.stamp.toNSec(), ros::Time::now().toNSec()))
        ROS_WARN("comm_broker: %s", skew->c_str());
    offered_[{r, m.index}] = ros_glue::offeredKeyframeMeta(m);
    radio_.offer(r, m.index, std::move(payload));
    offered_pub_.publish(ros_glue::offeredMsg(radio_.nextIndex()));  // where a restarted front-end continues
    runPendingSteps();
  }

  void onPose(char r, const geometry_msgs::PoseStamped& m) {
    const Eigen::Vector3d p(m.pose.position.x, m.pose.position.y, m.pose.position.z);
    std::lock_guard<std::mutex> lock(mutex_);
    if (!radio_.positionReported(r, p))
      ROS_WARN_THROTTLE(5.0, "comm_broker: /%c/reference_pose: non-finite position ignored", r);
  }

  /// Real time: every step of the grid up to ROS time now, catching up when time jumps.
  void onTimer() {
    const ros::Time now_ros = ros::Time::now();
    if (now_ros.isZero()) return;  // sim time before the first /clock
    std::lock_guard<std::mutex> lock(mutex_);
    const RadioBroker::StepBatch batch = radio_.stepRealTime(
        now_ros.toSec(), [this](const RadioBroker::Delivery& d) { return deliver(d, ros::Time(d.step_time)); });
    if (batch.grid_restarted)
      ROS_WARN("comm_broker: ROS time jumped forward by more than an hour; restarting the step grid");
    if (batch.time_went_back)
      ROS_WARN_THROTTLE(5.0, "comm_broker: ROS time went backwards (%.3f s < %.3f s); waiting", now_ros.toSec(),
                        radio().nextStepTime());
    if (batch.steps > 0) publishRadioState(now_ros, batch.last_time, batch.last_time, batch.links);
  }

  // Lockstep: the player's resolved sequence (latched): grid origin and radio seed, then every robot's reference.
  void onSequence(const cosmo::TeamSequence::ConstPtr& msg) {
    const cosmo::TeamSequence& m = *msg;
    std::lock_guard<std::mutex> lock(mutex_);
    sequence_name_ = m.name;
    const std::vector<char> in_sequence(m.robots.begin(), m.robots.end());
    for (char r : radio_.setSequence(m.start.toNSec(), m.seed, in_sequence))
      ROS_ERROR("comm_broker: robot %c is not in the player's sequence (%s): positions from its reference_pose", r,
                m.robots.c_str());
    startLockstep();
  }

  void onTrajectory(char r, const cosmo::ReferenceTrajectory& m) {
    Trajectory reference;
    try {
      reference = ros_glue::trajectoryFromMsg(m, ros_glue::referenceTrajectoryTopic(r));
    } catch (const std::exception& e) { ROS_ERROR("comm_broker: %s; positions from its reference_pose", e.what()); }
    std::lock_guard<std::mutex> lock(mutex_);
    radio_.setReference(r, std::move(reference));
    startLockstep();
  }

  // Lockstep, with the mutex held, once the sequence and every reference arrived: the front-ends connected, the
  // radio started; then the requests waiting for it run.
  void startLockstep() {
    if (!radio_.readyToStart()) return;
    waitForFrontends();
    const std::uint64_t seed = radio_.start();
    ROS_INFO("comm_broker: lockstep on sequence %s: radio seed %llu, grid origin %.3f s", sequence_name_.c_str(),
             static_cast<unsigned long long>(seed), toSeconds(radio_.origin()));
    runPendingSteps();
  }

  // Every front-end's offers and deliveries connected (a message sent before its connection exists is lost).
  void waitForFrontends() {
    const auto missing = [&] {
      std::string robots;
      std::size_t i = 0;
      for (char r : radio().robots())
        if (keyframe_subs_[i++].getNumPublishers() == 0 || received_pubs_.at(r).getNumSubscribers() == 0) robots += r;
      return robots;
    };
    // No limit here: the player stops the run when a front-end never connects (its peer policy).
    while (ros::ok() && !ros_glue::waitUntil([&] { return missing().empty(); }, ros_glue::wallDeadline(10.0)))
      ROS_INFO(
          "comm_broker: lockstep: waiting for the front-ends of robots %s (/<r>/keyframe_scans from it, "
          "/<r>/received_scans to it); the player stops the run if one never connects",
          missing().c_str());
  }

  void onStepRequest(const cosmo::RadioStepRequest::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    radio_.request(ros_glue::radioStepFromMsg(*m));
    runPendingSteps();
  }

  // Lockstep, with the mutex held: the requests that are ready, in order, each answered after its deliveries and
  // the radio's state.
  void runPendingSteps() {
    radio_.runReadySteps(
        [this](const RadioBroker::Delivery& d) { return deliver(d, ros_glue::stampToRos(d.step_stamp)); },
        [this](const RadioBroker::StepDone& done) {
          if (done.steps > 0)
            publishRadioState(ros_glue::stampToRos(done.last_step), toSeconds(done.last_step - radio_.origin()),
                              toSeconds(done.last_step), lastStepLinks(radio()));
          step_done_pub_.publish(ros_glue::radioStepDoneMsg(done));
        });
  }

  // Called with the mutex held. `when`: the step the transfer ended in. True when the scan was published.
  bool deliver(const RadioBroker::Delivery& d, const ros::Time& when) {
    const comm::Transfer& x = d.transfer;
    if (!d.delivered()) {
      ROS_DEBUG("comm_broker: %c -> %c keyframe %zu timed out", x.sender, x.receiver, x.keyframe);
      return false;
    }
    if (!d.error.empty()) {
      ROS_ERROR("comm_broker: keyframe %c%zu: %s", x.sender, x.keyframe, d.error.c_str());
      return false;
    }
    const auto it = offered_.find({x.sender, x.keyframe});
    if (it == offered_.end() || !d.scan) return false;
    received_pubs_.at(x.receiver).publish(ros_glue::deliveredKeyframeMsg(it->second, *d.scan, x, when));
    ROS_DEBUG("comm_broker: delivered %c%zu to %c (%zu bytes, %.1f s)", x.sender, x.keyframe, x.receiver, x.bytes,
              x.end - x.start);
    return true;
  }

  /// After a batch of steps, the latest at `radio_time`: link markers, /comm/stats (at `stats_time`), the log.
  void publishRadioState(const ros::Time& stamp, double radio_time, double stats_time,
                         const RadioBroker::Links& links) {
    links_pub_.publish(ros_glue::linkMarkers(radio(), links, radio_time, o_.frame_id, stamp));
    stats_pub_.publish(ros_glue::radioStatsMsg(radio(), stats_time));
    log_.writeEvery30s(radio(), radio_time);
  }

  ros_glue::CommBrokerOptions o_;
  std::mutex mutex_;
  RadioBroker radio_;
  live::ClockSkewWatch clock_skew_;                                  ///< live robots' clocks, from their offers' stamps
  std::map<std::pair<char, std::size_t>, cosmo::Keyframe> offered_;  ///< what deliveries carry besides the scan
  ros_glue::TransferLogFile log_{o_.log_file};
  std::string sequence_name_;
  ros::WallTimer timer_;
  std::vector<ros::Subscriber> keyframe_subs_, pose_subs_, trajectory_subs_;
  std::map<char, ros::Publisher> received_pubs_;
  ros::Subscriber sequence_sub_, step_request_sub_;
  ros::Publisher links_pub_, stats_pub_, step_done_pub_, offered_pub_;
};

}  // namespace

int main(int argc, char** argv) {
  ros_glue::initNode(argc, argv, "comm_broker");
  return ros_glue::runNode("comm_broker", [] {
    ros::NodeHandle nh, pnh("~");
    CommBroker broker(nh, ros_glue::readCommBrokerOptions(pnh));
    ros::AsyncSpinner spinner(2);  // compression of offered scans does not hold up the steps
    spinner.start();
    ros::waitForShutdown();
    spinner.stop();
    broker.writeLog();
  });
}
