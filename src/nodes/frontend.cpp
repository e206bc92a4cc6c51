// frontend: one robot's front-end (frontend::RobotFrontend) in namespace /<r>. It turns messages into the
// front-end's inputs (add: own scans, teammates' scans, reference and odometry poses) and publishes each step
// (ros_glue::FrontendPublisher); the rules are the core's. Topics, parameters, lockstep and real time: docs/nodes.md.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include <functional>
#include <memory>
#include <optional>

#include "cosmo/Keyframe.h"
#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/frontend/pending_scans.hpp"
#include "cosmo/frontend/robot_frontend.hpp"
#include "cosmo/ros/frontend_msgs.hpp"
#include "cosmo/ros/frontend_options.hpp"
#include "cosmo/ros/frontend_publisher.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/recorder_link.hpp"
#include "cosmo/ros/scan_input.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {

class FrontendNode {
 public:
  FrontendNode(ros::NodeHandle& nh, ros_glue::FrontendOptions options)
      : o_(std::move(options)),
        params_(ros_glue::frontendParams(o_)),
        recorder_(nh, o_.robot, !o_.lockstep, o_.recorder_wait),
        out_(nh, o_.robot, o_.world_frame, recorder_, ros_glue::markerNoiseModels(o_)),
        pending_(toStampNs(o_.reference_wait), !o_.lockstep) {
    subscribe(nh);
    ros_glue::logFrontendStart(o_);
  }

  /// At the end: what it processed and skipped, its queue's and its memory's peaks (docs/benchmarks.md).
  void summary() const { out_.summary(frontend_.get(), scansSkipped(), scans_ ? scans_->peak() : 0); }

 private:
  void subscribe(ros::NodeHandle& nh) {
    scans_.emplace(
        nh, "points", o_.lockstep ? 0 : static_cast<std::size_t>(o_.scan_queue),
        [this](const sensor_msgs::PointCloud2::ConstPtr& m) { onPoints(m); }, !o_.lockstep);
    recv_sub_ = nh.subscribe("received_scans", 100, &FrontendNode::onReceived, this);
    if (o_.odometry == "external") odom_sub_ = nh.subscribe("odom", 1000, &FrontendNode::onOdom, this);
    if (!o_.lockstep) {  // real time: the numbering decided (a restart?) before the first scan; acks every second
      ref_sub_ = nh.subscribe("reference_pose", 1000, &FrontendNode::onReference, this);
      start_timer_ = nh.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) { start(); });
      ack_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { ack(lastStamp()); });
      return;
    }
    // lockstep: the sequence's own reference; nothing else crosses the network
    trajectory_sub_ = nh.subscribe("reference_trajectory", 1, &FrontendNode::onTrajectory, this);
    waiting_timer_ = nh.createWallTimer(ros::WallDuration(10.0), [this](const ros::WallTimerEvent&) {
      if (frontend_) return waiting_timer_.stop();
      ROS_WARN("frontend %c: no sequence from the player yet (%s): %s", o_.robot, trajectory_sub_.getTopic().c_str(),
               ros_glue::whereThisNodeIs().c_str());
    });
  }

  // The front-end is built once, when all it is built with is known: lockstep, the sequence's reference trajectory
  // (the player's, latched); real time, the numbering (a restart continues its robot's) and the first input (the
  // player's sequence, whose registration keys apply, is resolved before anything is played). Inputs that come
  // earlier wait here, in order.
  void build(Trajectory reference) {
    frontend_ = std::make_unique<frontend::RobotFrontend>(
        o_.robot, ros_glue::frontendSetup(o_, params_, std::move(reference), recorder_.continuation().first_index));
    std::vector<std::function<void()>> early;
    early.swap(early_);
    for (const auto& input : early) input();
    drainPending();
  }

  /// Real time: builds the front-end once the numbering is decided and an input arrived.
  void buildWhenReady() {
    if (frontend_ || o_.lockstep || !recorder_.decided() || (early_.empty() && pending_.size() == 0)) return;
    build({});
  }

  /// `input` now, or once the front-end is built.
  void whenBuilt(std::function<void()> input) {
    if (frontend_) return input();
    early_.push_back(std::move(input));
    buildWhenReady();
  }

  // Real time: once the numbering is decided, the scans go ahead.
  void start() {
    if (!recorder_.decided()) return;
    start_timer_.stop();
    scans_->resume();
    buildWhenReady();
  }

  std::uint32_t scansSkipped() const {
    return recorder_.continuation().scans_skipped + static_cast<std::uint32_t>(scans_ ? scans_->skipped() : 0);
  }

  StampNs lastStamp() const { return frontend_ ? frontend_->lastStamp() : 0; }

  void tell(const frontend::Step& step, const std::string& topic) const {
    for (const std::string& n : step.notices)
      ROS_WARN_THROTTLE(5.0, "frontend %c: %s: %s", o_.robot, topic.c_str(), n.c_str());
  }

  void onReference(const geometry_msgs::PoseStamped::ConstPtr& m) {
    whenBuilt([this, m] {
      tell(frontend_->add(frontend::ReferencePose{m->header.stamp.toNSec(), ros_glue::poseFromMsg(m->pose)}),
           ref_sub_.getTopic());
      drainPending();
    });
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    whenBuilt([this, m] {
      frontend_->add(frontend::OdometryPose{m->header.stamp.toNSec(), ros_glue::poseFromMsg(m->pose.pose)});
    });
  }

  // Lockstep: built with the sequence's reference trajectory (the player's, latched) before its first scan. The
  // markers' inlier / outlier colours use the noise models the recorder labels with: without ~noise_models, those
  // the player's sequence names (none: the colours stay unlabelled).
  void onTrajectory(const cosmo::ReferenceTrajectory::ConstPtr& m) {
    if (frontend_) return;
    Trajectory reference;
    try {
      reference = ros_glue::trajectoryFromMsg(*m, trajectory_sub_.getTopic());
      if (!out_.map().hasNoiseModels()) {
        if (std::optional<dataset::NoiseModels> noise = ros_glue::sequenceNoiseModels(o_))
          out_.map().setNoiseModels(std::move(*noise));
      }
      if (reference.empty()) ROS_WARN("frontend %c: the sequence has no reference for this robot", o_.robot);
    } catch (const std::exception& e) { ROS_ERROR("frontend %c: lockstep: %s; no reference", o_.robot, e.what()); }
    build(std::move(reference));
  }

  void onPoints(const sensor_msgs::PointCloud2::ConstPtr& m) {
    pending_.push(m->header.stamp.toNSec(), m);
    buildWhenReady();
    drainPending();
  }

  // Scans wait (frontend::PendingScans) until the reference covers their stamp; lockstep: until the front-end is built.
  void drainPending() {
    if (!frontend_) return;
    const std::optional<StampNs> reference_end =
        frontend_->hasReference() ? std::optional<StampNs>(frontend_->reference().endStamp()) : std::nullopt;
    while (std::optional<sensor_msgs::PointCloud2::ConstPtr> m = pending_.popReady(reference_end)) process(**m);
  }

  /// Decoded (stamped at the sweep end, trials/point_cloud_decode.hpp), one step, published; acknowledged whatever
  /// happened to it.
  void process(const sensor_msgs::PointCloud2& m) {
    try {
      const Scan scan = ros_glue::fromPointCloud2(m, o_.stamp == "end", scans_->topic());
      const frontend::Step step = frontend_->add(frontend::OwnScan::of(scan));
      tell(step, scans_->topic());
      if (!step.dropped) out_.ownScan(*frontend_, step, ros_glue::stampToRos(scan.stamp), scansSkipped());
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "frontend %c: %s: %s", o_.robot, scans_->topic().c_str(), e.what());
    }
    ack(m.header.stamp.toNSec());
  }

  void onReceived(const cosmo::Keyframe::ConstPtr& m) {
    whenBuilt([this, m] { received(*m); });
  }

  void received(const cosmo::Keyframe& m) {
    try {
      const frontend::Step step =
          frontend_->add(ros_glue::teammateScanFromMsg(m, o_.robot, recv_sub_.getTopic(), ros::Time::now().toNSec()));
      out_.teammateScan(*frontend_, step, m);
    } catch (const std::exception& e) {
      ++received_dropped_;
      ROS_ERROR("frontend %c: %s: %s", o_.robot, recv_sub_.getTopic().c_str(), e.what());
    }
    ack(lastStamp());  // the player's lockstep counts processed deliveries
  }

  void ack(StampNs stamp) {
    out_.ack(frontend_.get(), stamp, received_dropped_, scans_ ? scans_->queued() : 0, scansSkipped());
  }

  ros_glue::FrontendOptions o_;
  frontend::FrontendParams params_;
  ros_glue::RecorderLink recorder_;  ///< numbered measurements to the recorder, kept until acknowledged
  ros_glue::FrontendPublisher out_;  ///< what each step publishes
  std::unique_ptr<frontend::RobotFrontend> frontend_;  ///< built once (build())
  frontend::PendingScans<sensor_msgs::PointCloud2::ConstPtr> pending_;
  std::vector<std::function<void()>> early_;  ///< inputs that came before the front-end was built
  std::size_t received_dropped_ = 0;
  ros::Subscriber ref_sub_, recv_sub_, odom_sub_, trajectory_sub_;
  ros::WallTimer start_timer_, ack_timer_, waiting_timer_;
  std::optional<ros_glue::ScanInput> scans_;  ///< last: its thread ends before the rest goes
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  // Ends with the process that started it (team_launcher, roslaunch): a front-end never outlives its launch.
  if (!ros_glue::endWithParent()) return 1;
  ros_glue::initNode(argc, argv, "frontend");
  return ros_glue::runNode("frontend", [] {
    ros::NodeHandle nh, pnh("~");
    FrontendNode node(nh, ros_glue::readFrontendOptions(pnh));
    ros::spin();  // single-threaded: scans and received scans are processed in arrival order
    node.summary();
  });
}
