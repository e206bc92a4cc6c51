// frontend: one robot's front-end (cosmo::pipeline::RobotFrontend) in namespace /<r>.
//
// Subscribes  points          (sensor_msgs/PointCloud2) the robot's LiDAR; remap to any robot's topic
//             reference_pose  (geometry_msgs/PoseStamped, world) the LiDAR's reference pose (optional)
//             odom            (nav_msgs/Odometry) external odometry when ~odometry external (remappable)
//             received_scans  (cosmo/Keyframe) teammates' scans delivered by the comm_broker
// Publishes   keyframe_scans  (cosmo/Keyframe) keyframe scans offered to the comm_broker
//             keyframes_meas  (cosmo/RecorderKeyframe), loop_closures (cosmo/RecorderLoopClosure) for the recorder
//             ack             (cosmo/FrontendAck: last scan processed, scans / teammate scans processed,
//                             keyframes offered, loop closures published) after every scan and delivery, for the
//                             player's lockstep mode
//             markers         (visualization_msgs/MarkerArray, frame world): trajectory, keyframes, loop closures
//                             (green accepted inlier, orange accepted outlier vs. the reference, red rejected;
//                             blue accepted when there is no reference)
//             TF <r>/odom -> <r>/base_link (odometry) and world -> <r>/odom (alignment: reference of keyframe 0,
//             identity without a reference)
// Params      ~robot (default: the namespace), ~config_dir (frontend/odometry/place_recognition/registration
//             .yaml), ~odometry loam|reference|external, ~noise_models (YAML, for the inlier/outlier colours),
//             ~world_frame (world), ~reference_wait (s of message time a scan waits for its reference pose; without
//             any reference, live use, scans are processed this much later), ~lockstep (false), ~stamp end|start
//             (the sweep instant of the points' header stamp; scans are processed stamped at the sweep end)
// Lockstep (~lockstep true, sequence.launch mode:=lockstep): the reference trajectory is the player's sequence's
//   own (ros_glue::readResolvedSequence: the CSV as the offline driver reads it, not the rounded reference_pose
//   messages, which are ignored), reference odometry takes it held at the ends as TeamRun does, and loop
//   closures on delivered scans are stamped with the broker's delivery step (Keyframe.received_at); with the
//   bit-exact pose fields of the recorder messages this makes the JRL byte-identical to cosmo_generate's.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include <optional>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <deque>
#include <map>

#include "cosmo/common/allocator_tuning.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/FrontendAck.h"
#include "cosmo/Keyframe.h"
#include "cosmo/RecorderKeyframe.h"
#include "cosmo/RecorderLoopClosure.h"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/pipeline/robot_frontend.hpp"
#include "cosmo/ros/point_cloud.hpp"

using namespace cosmo;

namespace {


geometry_msgs::Point point(const Eigen::Vector3d& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

std_msgs::ColorRGBA color(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA robotColor(char r) {
  static const float palette[][3] = {{0.2f, 0.6f, 1.0f}, {1.0f, 0.5f, 0.1f}, {0.7f, 0.3f, 0.9f},
                                     {0.1f, 0.8f, 0.7f}, {0.9f, 0.8f, 0.1f}, {0.9f, 0.3f, 0.5f}};
  const auto& c = palette[static_cast<unsigned>(r - 'a') % 6];
  return color(c[0], c[1], c[2]);
}

class FrontendNode {
 public:
  FrontendNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    std::string ns = ros::this_node::getNamespace();
    while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
    std::string robot;
    pnh.param<std::string>("robot", robot, ns);
    if (robot.size() != 1 || robot[0] < 'a' || robot[0] > 'z')
      throw std::runtime_error("~robot must be one lower-case letter (or run in namespace /<r>), got '" + robot + "'");
    robot_ = robot[0];
    std::string config_dir, noise;
    pnh.param<std::string>("config_dir", config_dir, pipeline::defaultConfigDir());
    pnh.param<std::string>("odometry", odometry_mode_, "loam");
    pnh.param<std::string>("noise_models", noise, "");
    pnh.param<std::string>("world_frame", world_frame_, "world");
    pnh.param("reference_wait", reference_wait_, 0.5);
    pnh.param("lockstep", lockstep_, false);
    std::string stamp_convention;
    pnh.param<std::string>("stamp", stamp_convention, "end");
    if (stamp_convention != "end" && stamp_convention != "start")
      throw std::runtime_error("~stamp must be start or end (the sweep instant of the header stamp), got '" +
                               stamp_convention + "'");
    stamp_at_end_ = stamp_convention == "end";
    frontend_params_ = pipeline::FrontendParams::loadDir(config_dir);
    if (odometry_mode_ != "loam" && odometry_mode_ != "reference" && odometry_mode_ != "external")
      throw std::runtime_error("~odometry must be loam, reference or external, got '" + odometry_mode_ + "'");
    if (!noise.empty()) noise_ = NoiseModels::load(noise);  // none: loop-closure markers without labels
    frontend_ = std::make_unique<pipeline::RobotFrontend>(robot_, frontend_params_);
    odom_frame_ = std::string(1, robot_) + "/odom";
    base_frame_ = std::string(1, robot_) + "/base_link";

    offer_pub_ = nh.advertise<cosmo::Keyframe>("keyframe_scans", 100);
    kf_pub_ = nh.advertise<cosmo::RecorderKeyframe>("keyframes_meas", 1000);
    lc_pub_ = nh.advertise<cosmo::RecorderLoopClosure>("loop_closures", 1000);
    ack_pub_ = nh.advertise<cosmo::FrontendAck>("ack", 100);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("markers", 5);
    points_sub_ = nh.subscribe("points", 5, &FrontendNode::onPoints, this);
    ref_sub_ = nh.subscribe("reference_pose", 1000, &FrontendNode::onReference, this);
    recv_sub_ = nh.subscribe("received_scans", 100, &FrontendNode::onReceived, this);
    if (odometry_mode_ == "external") odom_sub_ = nh.subscribe("odom", 1000, &FrontendNode::onOdom, this);
    ROS_INFO("frontend %c: odometry %s, config %s%s", robot_, odometry_mode_.c_str(), config_dir.c_str(),
             lockstep_ ? ", lockstep (reference from the player's sequence)" : "");
  }

 private:
  void onReference(const geometry_msgs::PoseStamped::ConstPtr& m) {
    if (lockstep_) return;  // the sequence's own reference (loadSequenceReference)
    frontend_->appendReference(m->header.stamp.toNSec(), ros_glue::poseFromMsg(m->pose));
    drainPending();
  }

  // Scans wait (in order) until the reference covers their stamp: the reference pose and the scan come on two
  // topics whose messages may arrive in either order. A scan older than the newest by more than
  // ~reference_wait seconds of message time goes ahead without (its keyframe then has no reference pose).
  void drainPending() {
    while (!pending_.empty()) {
      const StampNs stamp = pending_.front()->header.stamp.toNSec();
      const bool covered = frontend_->hasReference() && frontend_->reference().endStamp() >= stamp;
      const StampNs newest = pending_.back()->header.stamp.toNSec();
      const bool too_old = newest > stamp && newest - stamp > toStampNs(reference_wait_);
      if (!covered && !too_old && !lockstep_) return;  // lockstep: the reference is all there (or there is none)
      auto m = pending_.front();
      pending_.pop_front();
      process(m);
    }
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    odom_.emplace_back(m->header.stamp.toNSec(), ros_glue::poseFromMsg(m->pose.pose));
    while (odom_.size() > 2000) odom_.pop_front();
  }

  std::optional<Pose3> externalPoseAt(StampNs t) const {
    if (odom_.empty()) return std::nullopt;
    for (std::size_t i = odom_.size(); i-- > 1;) {
      if (odom_[i - 1].first <= t && t <= odom_[i].first) {
        const double span = static_cast<double>(odom_[i].first - odom_[i - 1].first);
        const double s = span > 0 ? static_cast<double>(t - odom_[i - 1].first) / span : 0.0;
        return interpolate(odom_[i - 1].second, odom_[i].second, s);
      }
    }
    if (t >= odom_.back().first && t - odom_.back().first < 200000000ULL) return odom_.back().second;
    return std::nullopt;
  }

  // Lockstep: before the first scan, the front-end is rebuilt with the sequence's reference trajectory.
  void loadSequenceReference() {
    if (sequence_loaded_) return;
    sequence_loaded_ = true;
    try {
      Trajectory reference = ros_glue::readResolvedSequence(30.0).reference(robot_);
      if (reference.empty()) ROS_WARN("frontend %c: the sequence has no reference for this robot", robot_);
      frontend_ = std::make_unique<pipeline::RobotFrontend>(robot_, frontend_params_, std::move(reference));
    } catch (const std::exception& e) {
      ROS_ERROR("frontend %c: lockstep: %s; no reference", robot_, e.what());
    }
  }

  void onPoints(const sensor_msgs::PointCloud2::ConstPtr& m) {
    if (lockstep_) loadSequenceReference();
    pending_.push_back(m);
    drainPending();
  }

  void process(const sensor_msgs::PointCloud2::ConstPtr& m) {
    const StampNs header_stamp = m->header.stamp.toNSec();  // acknowledged as received
    try {
      // Decoded with the topic's stamp convention: stamped at the sweep end as everywhere in the pipeline
      // (trials/point_cloud_decode.hpp); the player publishes scans stamped so.
      Scan scan = ros_glue::fromPointCloud2(*m, stamp_at_end_, points_sub_.getTopic());
      const StampNs stamp = scan.stamp;
      if (stamp <= frontend_->lastStamp() && frontend_->scansProcessed() > 0) {
        ROS_WARN_THROTTLE(5.0, "frontend %c: %s: stamp not increasing, scan dropped", robot_, points_sub_.getTopic().c_str());
      } else {
        pipeline::ScanOutcome out;
        if (odometry_mode_ == "reference" && lockstep_) {
          // as TeamRun: the reference held at its ends, LOAM without one
          out = frontend_->hasReference() ? frontend_->processScan(scan, frontend_->reference().atClamped(stamp))
                                          : frontend_->processScan(scan);
        } else if (odometry_mode_ == "reference") {
          const auto ref = frontend_->referenceAt(stamp);
          if (!ref) ROS_WARN_THROTTLE(5.0, "frontend %c: no reference pose at the scan stamp; using LOAM", robot_);
          out = ref ? frontend_->processScan(scan, *ref) : frontend_->processScan(scan);
        } else if (odometry_mode_ == "external") {
          const auto pose = externalPoseAt(stamp);
          if (!pose) {
            ROS_WARN_THROTTLE(5.0, "frontend %c: no external odometry at the scan stamp; scan dropped", robot_);
            ack(header_stamp);
            return;
          }
          out = frontend_->processScan(scan, *pose);
        } else {
          out = frontend_->processScan(scan);
          if (!out.odometry.ok) ROS_WARN_THROTTLE(5.0, "frontend %c: odometry: %s", robot_, out.odometry.warning.c_str());
        }
        handle(out, ros_glue::stampToRos(stamp));
      }
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "frontend %c: %s: %s", robot_, points_sub_.getTopic().c_str(), e.what());
    }
    ack(header_stamp);
  }

  void ack(StampNs stamp) {
    cosmo::FrontendAck a;
    a.header.stamp = ros_glue::stampToRos(stamp);
    a.header.frame_id = std::string(1, robot_);
    a.robot = a.header.frame_id;
    a.scans = static_cast<std::uint32_t>(frontend_->scansProcessed());
    a.received = static_cast<std::uint32_t>(frontend_->teammateScansReceived() + received_dropped_);
    a.keyframes = static_cast<std::uint32_t>(frontend_->keyframes().size());
    a.loop_closures = static_cast<std::uint32_t>(loop_closures_published_);
    ack_pub_.publish(a);
  }

  void handle(const pipeline::ScanOutcome& out, const ros::Time& stamp) {
    // world alignment: reference of keyframe 0 times odometry^-1
    if (out.keyframe && out.keyframe->index == 0 && out.keyframe->reference)
      world_T_odom_ = *out.keyframe->reference * out.keyframe->odom_pose.inverse();
    publishTf(out.odometry.pose, stamp);
    if (out.keyframe) {
      const auto& kf = *out.keyframe;
      cosmo::RecorderKeyframe km;
      km.header.stamp = ros_glue::stampToRos(kf.stamp);
      km.header.frame_id = world_frame_;
      km.robot = std::string(1, robot_);
      km.index = static_cast<std::uint32_t>(kf.index);
      km.odometry_from_previous = ros_glue::poseToMsg(kf.relative);
      km.odometry_from_previous_exact = ros_glue::poseToExact(kf.relative);
      km.has_reference = kf.reference.has_value();
      if (kf.reference) {
        km.reference = ros_glue::poseToMsg(*kf.reference);
        km.reference_exact = ros_glue::poseToExact(*kf.reference);
      }
      kf_pub_.publish(km);
      const std::shared_ptr<const Scan> s = frontend_->keyframeScan(kf.index);
      cosmo::Keyframe offer;
      offer.header.stamp = ros_glue::stampToRos(kf.stamp);
      offer.header.frame_id = base_frame_;
      offer.robot = km.robot;
      offer.index = km.index;
      offer.cloud = ros_glue::toPointCloud2(*s, base_frame_);
      offer.reference = km.reference;
      offer.has_reference = km.has_reference;
      offer_pub_.publish(offer);
      positions_[{robot_, kf.index}] = kf.reference ? kf.reference->translation() : (world_T_odom_ * kf.odom_pose).translation();
      trajectory_.push_back(positions_[{robot_, kf.index}]);
    }
    for (const auto& a : out.loop_closures) loopClosure(a);
    if (out.keyframe || !out.loop_closures.empty()) publishMarkers(stamp);
  }

  void onReceived(const cosmo::Keyframe::ConstPtr& m) {
    try {
      if (m->robot.size() != 1 || m->robot[0] == robot_) throw std::runtime_error("bad robot field '" + m->robot + "'");
      Scan scan = ros_glue::fromPointCloud2(m->cloud, true, recv_sub_.getTopic());
      scan.stamp = m->header.stamp.toNSec();
      if (m->has_reference) positions_[{m->robot[0], m->index}] = ros_glue::poseFromMsg(m->reference).translation();
      if (m->has_reference) references_[{m->robot[0], m->index}] = ros_glue::poseFromMsg(m->reference);
      // computed at the delivery's radio step (the offline driver's time); a broker without it: now
      const StampNs now = m->received_at.isZero() ? ros::Time::now().toNSec() : m->received_at.toNSec();
      for (const auto& a : frontend_->receiveTeammateScan(m->robot[0], m->index, scan, now)) loopClosure(a);
      publishMarkers(ros::Time::now());
    } catch (const std::exception& e) {
      ++received_dropped_;
      ROS_ERROR("frontend %c: %s: %s", robot_, recv_sub_.getTopic().c_str(), e.what());
    }
    ack(frontend_->lastStamp());  // the player's lockstep counts processed deliveries
  }

  void loopClosure(const pipeline::LoopClosureAttempt& a) {
    Marked mk{a, 0};
    if (a.accepted) {
      cosmo::RecorderLoopClosure lc;
      lc.header.stamp = ros_glue::stampToRos(a.computed_at);
      lc.header.frame_id = world_frame_;
      lc.owner = std::string(1, a.owner);
      lc.robot1 = std::string(1, a.robot1);
      lc.index1 = static_cast<std::uint32_t>(a.index1);
      lc.robot2 = std::string(1, a.robot2);
      lc.index2 = static_cast<std::uint32_t>(a.index2);
      lc.measurement = ros_glue::poseToMsg(a.measurement);
      lc.measurement_exact = ros_glue::poseToExact(a.measurement);
      lc_pub_.publish(lc);
      ++loop_closures_published_;
      // inlier / outlier against the reference when both poses have one
      const auto r1 = referenceOf(a.robot1, a.index1), r2 = referenceOf(a.robot2, a.index2);
      if (r1 && r2 && noise_) mk.state = isOutlier(a.measurement, r1->inverse() * *r2, noise_->loop_closure) ? 2 : 1;
      else mk.state = 3;
    }
    ROS_INFO("frontend %c: loop closure %c%zu-%c%zu %s (%zu inliers, descriptor %.3f)", robot_, a.robot1, a.index1,
             a.robot2, a.index2, a.accepted ? "accepted" : a.reason.c_str(), a.inliers, a.descriptor_distance);
    closures_.push_back(mk);
  }

  std::optional<Pose3> referenceOf(char r, std::size_t i) const {
    if (r == robot_) {
      const auto& kfs = frontend_->keyframes();
      return i < kfs.size() ? kfs[i].reference : std::nullopt;
    }
    auto it = references_.find({r, i});
    return it == references_.end() ? std::nullopt : std::optional<Pose3>(it->second);
  }

  void publishTf(const Pose3& odom_pose, const ros::Time& stamp) {
    auto tfOf = [&](const Pose3& T, const std::string& parent, const std::string& child) {
      geometry_msgs::TransformStamped t;
      t.header.stamp = stamp;
      t.header.frame_id = parent;
      t.child_frame_id = child;
      const auto p = ros_glue::poseToMsg(T);
      t.transform.translation.x = p.position.x;
      t.transform.translation.y = p.position.y;
      t.transform.translation.z = p.position.z;
      t.transform.rotation = p.orientation;
      return t;
    };
    tf_.sendTransform({tfOf(world_T_odom_, world_frame_, odom_frame_), tfOf(odom_pose, odom_frame_, base_frame_)});
  }

  void publishMarkers(const ros::Time& stamp) {
    visualization_msgs::MarkerArray arr;
    visualization_msgs::Marker traj, kfs, lcs;
    for (auto* m : {&traj, &kfs, &lcs}) {
      m->header.stamp = stamp;
      m->header.frame_id = world_frame_;
      m->pose.orientation.w = 1.0;
      m->action = visualization_msgs::Marker::ADD;
    }
    const std::string ns(1, robot_);
    traj.ns = ns + "/trajectory";
    traj.type = visualization_msgs::Marker::LINE_STRIP;
    traj.scale.x = 0.3;
    traj.color = robotColor(robot_);
    kfs.ns = ns + "/keyframes";
    kfs.type = visualization_msgs::Marker::SPHERE_LIST;
    kfs.scale.x = kfs.scale.y = kfs.scale.z = 0.8;
    kfs.color = robotColor(robot_);
    for (const auto& p : trajectory_) {
      traj.points.push_back(point(p));
      kfs.points.push_back(point(p));
    }
    lcs.ns = ns + "/loop_closures";
    lcs.type = visualization_msgs::Marker::LINE_LIST;
    lcs.scale.x = 0.4;
    lcs.color = color(1, 1, 1);
    // closures join keyframes a few metres apart: lift them above the trajectories so they stay visible
    constexpr double kClosureLift = 1.5;
    auto lifted = [&](const Eigen::Vector3d& v) {
      geometry_msgs::Point q = point(v);
      q.z += kClosureLift;
      return q;
    };
    for (const auto& c : closures_) {
      auto p1 = positions_.find({c.a.robot1, c.a.index1});
      auto p2 = positions_.find({c.a.robot2, c.a.index2});
      if (p1 == positions_.end() || p2 == positions_.end()) continue;
      const std_msgs::ColorRGBA col = c.state == 0   ? color(0.9f, 0.1f, 0.1f, 0.5f)
                                      : c.state == 1 ? color(0.1f, 0.9f, 0.2f)
                                      : c.state == 2 ? color(1.0f, 0.6f, 0.0f)
                                                     : color(0.2f, 0.4f, 1.0f);
      lcs.points.push_back(lifted(p1->second));
      lcs.points.push_back(lifted(p2->second));
      lcs.colors.push_back(col);
      lcs.colors.push_back(col);
    }
    // rviz flags an empty or one-point line marker as an error: delete it until it has content
    if (traj.points.size() < 2) {
      traj.points.clear();
      traj.action = visualization_msgs::Marker::DELETE;
    }
    if (lcs.points.empty()) lcs.action = visualization_msgs::Marker::DELETE;
    arr.markers = {traj, kfs, lcs};
    marker_pub_.publish(arr);
  }

  struct Marked {
    pipeline::LoopClosureAttempt a;
    int state;  ///< 0 rejected, 1 accepted inlier, 2 accepted outlier, 3 accepted (no reference)
  };

  char robot_ = 'a';
  std::string odometry_mode_, world_frame_, odom_frame_, base_frame_;
  std::optional<NoiseModels> noise_;  ///< for the markers' inlier / outlier colours only
  std::unique_ptr<pipeline::RobotFrontend> frontend_;
  Pose3 world_T_odom_ = Pose3::Identity();
  std::deque<std::pair<StampNs, Pose3>> odom_;
  std::map<std::pair<char, std::size_t>, Eigen::Vector3d> positions_;
  std::map<std::pair<char, std::size_t>, Pose3> references_;
  std::vector<Eigen::Vector3d> trajectory_;
  std::vector<Marked> closures_;
  std::size_t received_dropped_ = 0;
  std::size_t loop_closures_published_ = 0;  ///< counted in the ack (the player's end-of-run handshake)
  std::deque<sensor_msgs::PointCloud2::ConstPtr> pending_;
  double reference_wait_ = 0.5;
  bool lockstep_ = false, sequence_loaded_ = false;
  bool stamp_at_end_ = true;  ///< ~stamp: the points topic's header stamp is the sweep end (else its start)
  pipeline::FrontendParams frontend_params_;
  ros::Publisher offer_pub_, kf_pub_, lc_pub_, ack_pub_, marker_pub_;
  ros::Subscriber points_sub_, ref_sub_, recv_sub_, odom_sub_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace

int main(int argc, char** argv) {
  cosmo::keepScanBuffersInProcess();
  ros::init(argc, argv, "frontend");
  ros::NodeHandle nh, pnh("~");
  try {
    FrontendNode node(nh, pnh);
    ros::spin();  // single-threaded: scans and received scans are processed in arrival order
  } catch (const std::exception& e) {
    ROS_FATAL("frontend: %s", e.what());
    return 1;
  }
  return 0;
}
