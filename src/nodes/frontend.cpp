// frontend: one robot's front-end (cosmo::pipeline::RobotFrontend) in namespace /<r>.
//
// Subscribes  points          (sensor_msgs/PointCloud2) the robot's LiDAR; remap to any robot's topic
//             reference_trajectory (cosmo/ReferenceTrajectory, latched) the whole reference, lockstep only
//             reference_pose  (geometry_msgs/PoseStamped, world) the LiDAR's reference pose (optional)
//             odom            (nav_msgs/Odometry) external odometry when ~odometry external (remappable)
//             received_scans  (cosmo/Keyframe) teammates' scans delivered by the comm_broker
// Publishes   keyframe_scans  (cosmo/Keyframe) keyframe scans offered to the comm_broker
//             keyframes_meas  (cosmo/RecorderKeyframe), loop_closures (cosmo/RecorderLoopClosure) for the recorder
//             ack             (cosmo/FrontendAck: last scan processed, scans / teammate scans processed,
//                             keyframes offered, loop closures published, the last measurement number sent, scans
//                             waiting and skipped) after every scan and delivery (real time: also every second)
//             markers         (visualization_msgs/MarkerArray, frame world): trajectory, keyframes, loop closures
//                             (green accepted inlier, orange accepted outlier vs. the reference, red rejected;
//                             blue accepted when there is no reference)
//             TF <r>/odom -> <r>/base_link (odometry) and world -> <r>/odom (alignment: reference of keyframe 0,
//             identity without a reference)
// The recorder (ros_glue::RecorderLink): every measurement is numbered and kept until /recorder/progress
//   acknowledges it, and sent again to a respawned recorder. Real time: the scans wait in a bounded queue of
//   ~scan_queue scans (the oldest waiting one is skipped when it is full, counted in the ack and the keyframes:
//   ros_glue::ScanInput), and a front-end that starts while the recorder holds measurements of its robot is a
//   restart: it continues the robot's keyframe indices and numbers, its first keyframe bridged (docs/design.md).
//   The node ends (SIGINT) when the process that started it ends (team_launcher, roslaunch).
// Params      ~robot (default: the namespace), ~config_dir (frontend/odometry/place_recognition/registration
//             .yaml), ~odometry loam|reference|external, ~noise_models (YAML, for the inlier/outlier colours;
//             empty in lockstep: the player's sequence's), ~world_frame (world), ~reference_wait (s of message
//             time a scan waits for its reference pose; without any reference, live use, scans are processed
//             this much later), ~lockstep (false), ~scan_queue (real time, default 10), ~recorder_wait (s a
//             starting front-end waits for the recorder's progress, default 10), ~stamp end|start
//             (the sweep instant of the points' header stamp; scans are processed stamped at the sweep end)
// Lockstep (~lockstep true, sequence.launch mode:=lockstep): the reference trajectory is the player's sequence's
//   own (reference_trajectory, cosmo/ReferenceTrajectory, latched: the CSV as the offline driver reads it, poses
//   bit-exact; reference_pose is not subscribed to; scans wait until it arrived), reference odometry takes
//   it held at the ends as TeamRun does, and loop closures on delivered scans are stamped with the broker's delivery
//   step (Keyframe.received_at); with the bit-exact pose fields of the recorder messages this makes the JRL
//   byte-identical to cosmo_generate's.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>

#include "cosmo/FrontendAck.h"
#include "cosmo/Keyframe.h"
#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/pipeline/external_odometry.hpp"
#include "cosmo/pipeline/frontend_map.hpp"
#include "cosmo/pipeline/pending_scans.hpp"
#include "cosmo/pipeline/robot_frontend.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/frontend_msgs.hpp"
#include "cosmo/ros/markers.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/recorder_link.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/scan_input.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {

struct Options {
  char robot = 'a';
  std::string config_dir, odometry = "loam", noise_models, world_frame = "world";
  double reference_wait = 0.5, recorder_wait = 10.0;
  int scan_queue = 10;
  bool lockstep = false;
  bool stamp_at_end = true;  ///< ~stamp: the points topic's header stamp is the sweep end (else its start)
};

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  std::string ns = ros::this_node::getNamespace(), robot, stamp = "end";
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  pnh.param<std::string>("robot", robot, ns);
  if (robot.size() != 1 || robot[0] < 'a' || robot[0] > 'z')
    throw std::runtime_error("~robot must be one lower-case letter (or run in namespace /<r>), got '" + robot + "'");
  o.robot = robot[0];
  pnh.param<std::string>("config_dir", o.config_dir, pipeline::defaultConfigDir());
  pnh.param<std::string>("odometry", o.odometry, o.odometry);
  pnh.param<std::string>("noise_models", o.noise_models, "");
  pnh.param<std::string>("world_frame", o.world_frame, o.world_frame);
  pnh.param("reference_wait", o.reference_wait, o.reference_wait);
  pnh.param("lockstep", o.lockstep, o.lockstep);
  pnh.param("scan_queue", o.scan_queue, o.scan_queue);
  pnh.param("recorder_wait", o.recorder_wait, o.recorder_wait);
  if (o.scan_queue < 1) throw std::runtime_error("~scan_queue must be at least 1, got " + std::to_string(o.scan_queue));
  pnh.param<std::string>("stamp", stamp, stamp);
  if (stamp != "end" && stamp != "start")
    throw std::runtime_error("~stamp must be start or end (the sweep instant of the header stamp), got '" + stamp +
                             "'");
  o.stamp_at_end = stamp == "end";
  if (o.odometry != "loam" && o.odometry != "reference" && o.odometry != "external")
    throw std::runtime_error("~odometry must be loam, reference or external, got '" + o.odometry + "'");
  return o;
}

/// ~noise_models for the loop-closure colours; none: unlabelled (lockstep: the sequence's, once it is known).
std::optional<NoiseModels> markerNoiseModels(const std::string& path) {
  if (path.empty()) return std::nullopt;
  return NoiseModels::load(path);
}

class FrontendNode {
 public:
  FrontendNode(ros::NodeHandle& nh, Options options)
      : o_(std::move(options)),
        params_(pipeline::FrontendParams::loadDir(o_.config_dir)),
        frontend_(std::make_unique<pipeline::RobotFrontend>(o_.robot, params_)),
        recorder_(nh, o_.robot, !o_.lockstep, o_.recorder_wait),
        map_(o_.robot, markerNoiseModels(o_.noise_models)),
        pending_(toStampNs(o_.reference_wait), !o_.lockstep),
        odom_frame_(std::string(1, o_.robot) + "/odom"),
        base_frame_(std::string(1, o_.robot) + "/base_link") {
    advertise(nh);
    subscribe(nh);
    ROS_INFO("frontend %c: odometry %s, config %s%s", o_.robot, o_.odometry.c_str(), o_.config_dir.c_str(),
             o_.lockstep ? ", lockstep (reference from the player's sequence)" : "");
    if (o_.lockstep && !ros::Time::isSimTime())
      ROS_WARN("frontend %c: /use_sim_time was not set when this node started: it runs on this machine's clock, not "
               "the player's /clock (start the base's launch first; the dataset does not depend on it)",
               o_.robot);
  }

  /// At the end: what it processed and skipped, its queue's and its memory's peaks (falling behind, docs/benchmarks.md).
  void summary() const {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("frontend %c: %zu scans processed, %u skipped, at most %zu waiting; %zu keyframes, %llu measurements "
                "sent, %zu not acknowledged; peak memory %.0f MB\n",
                o_.robot, frontend_->scansProcessed(), scansSkipped(), scans_ ? scans_->peak() : 0,
                frontend_->keyframes().size(), static_cast<unsigned long long>(recorder_.lastSeq()),
                recorder_.unacknowledged(), usage.ru_maxrss / 1024.0);
    std::fflush(stdout);
  }

 private:
  void advertise(ros::NodeHandle& nh) {
    offer_pub_ = nh.advertise<cosmo::Keyframe>("keyframe_scans", 100);
    ack_pub_ = nh.advertise<cosmo::FrontendAck>("ack", 100);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("markers", 5);
  }

  void subscribe(ros::NodeHandle& nh) {
    scans_.emplace(nh, "points", o_.lockstep ? 0 : static_cast<std::size_t>(o_.scan_queue),
                   [this](const sensor_msgs::PointCloud2::ConstPtr& m) { onPoints(m); }, !o_.lockstep);
    if (!o_.lockstep) {  // real time: the numbering decided (a restart?) before the first scan; acks every second
      start_timer_ = nh.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) { startWhenDecided(); });
      ack_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
        ack(frontend_->lastStamp());
      });
    }
    if (!o_.lockstep)  // lockstep: the sequence's own reference (onTrajectory); nothing else crosses the network
      ref_sub_ = nh.subscribe("reference_pose", 1000, &FrontendNode::onReference, this);
    recv_sub_ = nh.subscribe("received_scans", 100, &FrontendNode::onReceived, this);
    if (o_.lockstep) {
      trajectory_sub_ = nh.subscribe("reference_trajectory", 1, &FrontendNode::onTrajectory, this);
      waiting_timer_ = nh.createWallTimer(ros::WallDuration(10.0), [this](const ros::WallTimerEvent&) {
        if (sequence_loaded_) return waiting_timer_.stop();
        ROS_WARN("frontend %c: no sequence from the player yet (%s): %s", o_.robot, trajectory_sub_.getTopic().c_str(),
                 ros_glue::whereThisNodeIs().c_str());
      });
    }
    if (o_.odometry == "external") odom_sub_ = nh.subscribe("odom", 1000, &FrontendNode::onOdom, this);
  }

  /// A front-end numbering its keyframes where this one's numbering starts (a restart continues its robot's).
  std::unique_ptr<pipeline::RobotFrontend> makeFrontend(Trajectory reference) const {
    auto f = std::make_unique<pipeline::RobotFrontend>(o_.robot, params_, std::move(reference));
    f->numberKeyframesFrom(recorder_.continuation().first_index);
    return f;
  }

  // Real time: once the numbering is decided (a restart continues its robot's), the scans go ahead.
  void startWhenDecided() {
    if (!recorder_.decided()) return;
    start_timer_.stop();
    frontend_->numberKeyframesFrom(recorder_.continuation().first_index);  // no scan processed yet
    scans_->resume();
  }

  std::uint32_t scansSkipped() const {
    return recorder_.continuation().scans_skipped + static_cast<std::uint32_t>(scans_ ? scans_->skipped() : 0);
  }

  void onReference(const geometry_msgs::PoseStamped::ConstPtr& m) {
    if (o_.lockstep) return;  // the sequence's own reference (onTrajectory)
    useSequenceRegistrationOnce();
    frontend_->appendReference(m->header.stamp.toNSec(), ros_glue::poseFromMsg(m->pose));
    drainPending();
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    odom_.add(m->header.stamp.toNSec(), ros_glue::poseFromMsg(m->pose.pose));
  }

  // Lockstep: the front-end is rebuilt with the sequence's reference trajectory (the player's, latched) before
  // its first scan; scans that arrive earlier wait for it.
  void onTrajectory(const cosmo::ReferenceTrajectory::ConstPtr& m) {
    if (sequence_loaded_) return;
    sequence_loaded_ = true;
    try {
      Trajectory reference = ros_glue::trajectoryFromMsg(*m, trajectory_sub_.getTopic());
      if (!map_.hasNoiseModels()) {
        if (std::optional<NoiseModels> noise = sequenceNoiseModels()) map_.setNoiseModels(std::move(*noise));
      }
      if (reference.empty()) ROS_WARN("frontend %c: the sequence has no reference for this robot", o_.robot);
      useSequenceRegistration();
      frontend_ = makeFrontend(std::move(reference));
    } catch (const std::exception& e) { ROS_ERROR("frontend %c: lockstep: %s; no reference", o_.robot, e.what()); }
    drainPending();
  }

  // The registration setting of the player's sequence: its `registration:` keys (a parameter, no file read) on
  // top of ~config_dir's file, as cosmo_generate applies them. False when no player resolved a sequence.
  bool useSequenceRegistration() {
    const std::optional<ros_glue::ResolvedSequence> sequence = ros_glue::resolvedSequence();
    if (!sequence) return false;
    params_.registration = pipeline::registrationParamsWith(o_.config_dir, sequence->registration, sequence->path);
    if (!sequence->registration.empty())
      ROS_INFO("frontend %c: registration: %s's own keys over %s/registration.yaml", o_.robot, sequence->path.c_str(),
               o_.config_dir.c_str());
    return true;
  }

  // Real time: the same, once, before the front-end holds a reference pose or a scan (it is rebuilt empty).
  void useSequenceRegistrationOnce() {
    if (o_.lockstep || registration_resolved_) return;
    registration_resolved_ = true;
    try {
      if (useSequenceRegistration()) frontend_ = makeFrontend({});
    } catch (const std::exception& e) {
      ROS_ERROR("frontend %c: the player's sequence: %s; registration stays %s/registration.yaml's", o_.robot, e.what(),
                o_.config_dir.c_str());
    }
  }

  // The markers' inlier / outlier colours use the noise models the recorder labels with: without ~noise_models,
  // those the player's sequence names (its config file and the noise-model file it names are read; none: the
  // colours stay unlabelled).
  std::optional<NoiseModels> sequenceNoiseModels() const {
    const std::optional<ros_glue::ResolvedSequence> sequence = ros_glue::resolvedSequence();
    if (!sequence) return std::nullopt;
    try {
      return pipeline::loadSequenceNoiseModels(sequence->load(), o_.config_dir);
    } catch (const std::exception& e) {
      ROS_WARN("frontend %c: no noise models for the loop-closure colours: %s", o_.robot, e.what());
      return std::nullopt;
    }
  }

  void onPoints(const sensor_msgs::PointCloud2::ConstPtr& m) {
    pending_.push(m->header.stamp.toNSec(), m);
    drainPending();
  }

  // Scans wait (pipeline::PendingScans) until the reference covers their stamp; lockstep: until the sequence's
  // reference arrived.
  void drainPending() {
    if (o_.lockstep && !sequence_loaded_) return;
    const std::optional<StampNs> reference_end =
        frontend_->hasReference() ? std::optional<StampNs>(frontend_->reference().endStamp()) : std::nullopt;
    while (std::optional<sensor_msgs::PointCloud2::ConstPtr> m = pending_.popReady(reference_end)) process(**m);
  }

  /// Decode, one front-end step, publish; the scan is acknowledged whatever happened to it.
  void process(const sensor_msgs::PointCloud2& m) {
    useSequenceRegistrationOnce();
    try {
      // Decoded with the topic's stamp convention: stamped at the sweep end as everywhere in the pipeline
      // (trials/point_cloud_decode.hpp); the player publishes scans stamped so.
      const Scan scan = ros_glue::fromPointCloud2(m, o_.stamp_at_end, scans_->topic());
      if (scan.stamp <= frontend_->lastStamp() && frontend_->scansProcessed() > 0)
        ROS_WARN_THROTTLE(5.0, "frontend %c: %s: stamp not increasing, scan dropped", o_.robot,
                          scans_->topic().c_str());
      else if (const std::optional<pipeline::ScanOutcome> out = processScan(scan))
        publish(*out, ros_glue::stampToRos(scan.stamp));
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "frontend %c: %s: %s", o_.robot, scans_->topic().c_str(), e.what());
    }
    ack(m.header.stamp.toNSec());
  }

  /// The scan through the front-end with the odometry of ~odometry; none when external odometry has no pose.
  std::optional<pipeline::ScanOutcome> processScan(const Scan& scan) {
    if (o_.odometry == "reference" && o_.lockstep)  // as TeamRun: the reference held at its ends, LOAM without one
      return frontend_->hasReference() ? frontend_->processScan(scan, frontend_->reference().atClamped(scan.stamp))
                                       : frontend_->processScan(scan);
    if (o_.odometry == "reference") {
      const std::optional<Pose3> ref = frontend_->referenceAt(scan.stamp);
      if (!ref) ROS_WARN_THROTTLE(5.0, "frontend %c: no reference pose at the scan stamp; using LOAM", o_.robot);
      return ref ? frontend_->processScan(scan, *ref) : frontend_->processScan(scan);
    }
    if (o_.odometry == "external") {
      const std::optional<Pose3> pose = odom_.at(scan.stamp);
      if (!pose) ROS_WARN_THROTTLE(5.0, "frontend %c: no external odometry at the scan stamp; scan dropped", o_.robot);
      if (!pose) return std::nullopt;
      return frontend_->processScan(scan, *pose);
    }
    pipeline::ScanOutcome out = frontend_->processScan(scan);
    if (!out.odometry.ok) ROS_WARN_THROTTLE(5.0, "frontend %c: odometry: %s", o_.robot, out.odometry.warning.c_str());
    return out;
  }

  void publish(const pipeline::ScanOutcome& out, const ros::Time& stamp) {
    if (out.keyframe) map_.addKeyframe(*out.keyframe);  // first: keyframe 0 aligns the odometry with the world
    tf_.sendTransform({ros_glue::transformMsg(map_.worldFromOdometry(), stamp, o_.world_frame, odom_frame_),
                       ros_glue::transformMsg(out.odometry.pose, stamp, odom_frame_, base_frame_)});
    if (out.keyframe) publishKeyframe(*out.keyframe);
    for (const auto& a : out.loop_closures) loopClosure(a);
    if (out.keyframe || !out.loop_closures.empty()) publishMarkers(stamp);
  }

  /// To the recorder, and its scan offered to the teammates.
  void publishKeyframe(const pipeline::KeyframeRecord& kf) {
    const cosmo::RecorderKeyframe km = ros_glue::recorderKeyframeMsg(kf, o_.world_frame);
    cosmo::RecorderKeyframe measured = km;
    measured.scans_skipped = scansSkipped();
    recorder_.send(std::move(measured));
    offer_pub_.publish(ros_glue::keyframeOfferMsg(km, *frontend_->keyframeScan(kf.index), base_frame_));
  }

  void onReceived(const cosmo::Keyframe::ConstPtr& m) {
    try {
      if (m->robot.size() != 1 || m->robot[0] == o_.robot)
        throw std::runtime_error("bad robot field '" + m->robot + "'");
      Scan scan = ros_glue::fromPointCloud2(m->cloud, true, recv_sub_.getTopic());
      scan.stamp = m->header.stamp.toNSec();
      if (m->has_reference) map_.addTeammateKeyframe(m->robot[0], m->index, ros_glue::poseFromMsg(m->reference));
      // computed at the delivery's radio step (the offline driver's time); a broker without it: now
      const StampNs now = m->received_at.isZero() ? ros::Time::now().toNSec() : m->received_at.toNSec();
      for (const auto& a : frontend_->receiveTeammateScan(m->robot[0], m->index, scan, now)) loopClosure(a);
      publishMarkers(ros::Time::now());
    } catch (const std::exception& e) {
      ++received_dropped_;
      ROS_ERROR("frontend %c: %s: %s", o_.robot, recv_sub_.getTopic().c_str(), e.what());
    }
    ack(frontend_->lastStamp());  // the player's lockstep counts processed deliveries
  }

  void loopClosure(const pipeline::LoopClosureAttempt& a) {
    if (a.accepted) {
      recorder_.send(ros_glue::recorderLoopClosureMsg(a, o_.world_frame));
      ++loop_closures_published_;
    }
    ROS_DEBUG("frontend %c: loop closure %c%zu-%c%zu %s (%zu inliers, descriptor %.3f)", o_.robot, a.robot1, a.index1,
              a.robot2, a.index2, a.accepted ? "accepted" : a.reason.c_str(), a.inliers, a.descriptor_distance);
    map_.addClosure(a);
  }

  void ack(StampNs stamp) {
    cosmo::FrontendAck a;
    a.header.stamp = ros_glue::stampToRos(stamp);
    a.header.frame_id = std::string(1, o_.robot);
    a.robot = a.header.frame_id;
    a.scans = static_cast<std::uint32_t>(frontend_->scansProcessed());
    a.received = static_cast<std::uint32_t>(frontend_->teammateScansReceived() + received_dropped_);
    a.keyframes = static_cast<std::uint32_t>(frontend_->keyframes().size());
    a.loop_closures = static_cast<std::uint32_t>(loop_closures_published_);
    a.seq = recorder_.lastSeq();
    a.queued = static_cast<std::uint32_t>(scans_ ? scans_->queued() : 0);
    a.skipped = scansSkipped();
    ack_pub_.publish(a);
    ROS_INFO_THROTTLE(5.0,
                      "frontend %c: %u scans, %u keyframes, %u loop closures accepted of %zu tried, %u scans received",
                      o_.robot, a.scans, a.keyframes, a.loop_closures,
                      frontend_->loopClosuresAccepted() + frontend_->loopClosuresRejected(), a.received);
  }

  void publishMarkers(const ros::Time& stamp) {
    marker_pub_.publish(ros_glue::frontendMarkers(map_, o_.robot, o_.world_frame, stamp));
  }

  Options o_;
  pipeline::FrontendParams params_;
  std::unique_ptr<pipeline::RobotFrontend> frontend_;
  ros_glue::RecorderLink recorder_;  ///< numbered measurements to the recorder, kept until acknowledged
  pipeline::FrontendMap map_;  ///< what the markers show
  pipeline::PendingScans<sensor_msgs::PointCloud2::ConstPtr> pending_;
  pipeline::ExternalOdometry odom_;
  std::string odom_frame_, base_frame_;
  bool sequence_loaded_ = false;
  bool registration_resolved_ = false;  // real time: the player's sequence's registration keys looked up
  std::size_t received_dropped_ = 0;
  std::size_t loop_closures_published_ = 0;  ///< counted in the ack (the player's end-of-run handshake)
  ros::Publisher offer_pub_, ack_pub_, marker_pub_;
  ros::Subscriber ref_sub_, recv_sub_, odom_sub_, trajectory_sub_;
  ros::WallTimer start_timer_, ack_timer_;
  ros::WallTimer waiting_timer_;  ///< lockstep: says where it waits while the sequence has not arrived
  std::optional<ros_glue::ScanInput> scans_;  ///< last: its thread ends before the rest goes
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  // Ends with the process that started it (team_launcher, roslaunch): a front-end never outlives its launch.
  const pid_t parent = getppid();
  prctl(PR_SET_PDEATHSIG, SIGINT);
  if (getppid() != parent) return 1;  // the parent ended before prctl
  ros_glue::initNode(argc, argv, "frontend");
  return ros_glue::runNode("frontend", [] {
    ros::NodeHandle nh, pnh("~");
    FrontendNode node(nh, readOptions(pnh));
    ros::spin();  // single-threaded: scans and received scans are processed in arrival order
    node.summary();
  });
}
