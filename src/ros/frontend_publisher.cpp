#include "cosmo/ros/frontend_publisher.hpp"

#include <sys/resource.h>

#include <cstdio>

#include "cosmo/FrontendAck.h"
#include "cosmo/Keyframe.h"
#include "cosmo/ros/frontend_msgs.hpp"
#include "cosmo/ros/markers.hpp"
#include "cosmo/ros/pose_msg.hpp"

namespace cosmo::ros_glue {

FrontendPublisher::FrontendPublisher(ros::NodeHandle& nh, char robot, std::string world_frame, RecorderLink& recorder,
                                     std::optional<dataset::NoiseModels> noise)
    : robot_(robot),
      world_frame_(std::move(world_frame)),
      odom_frame_(std::string(1, robot) + "/odom"),
      base_frame_(std::string(1, robot) + "/base_link"),
      recorder_(recorder),
      map_(robot, std::move(noise)),
      offer_pub_(nh.advertise<cosmo::Keyframe>("keyframe_scans", 100)),
      ack_pub_(nh.advertise<cosmo::FrontendAck>("ack", 100)),
      marker_pub_(nh.advertise<visualization_msgs::MarkerArray>("markers", 5)) {}

void FrontendPublisher::ownScan(frontend::RobotFrontend& frontend, const frontend::Step& step, const ros::Time& stamp,
                                std::uint32_t scans_skipped) {
  if (step.keyframe) map_.addKeyframe(*step.keyframe);  // first: keyframe 0 aligns the odometry with the world
  tf_.sendTransform({transformMsg(map_.worldFromOdometry(), stamp, world_frame_, odom_frame_),
                     transformMsg(step.odometry.pose, stamp, odom_frame_, base_frame_)});
  if (step.keyframe) {
    const cosmo::RecorderKeyframe km = recorderKeyframeMsg(*step.keyframe, world_frame_);
    cosmo::RecorderKeyframe measured = km;
    measured.scans_skipped = scans_skipped;
    recorder_.send(std::move(measured));
    offer_pub_.publish(keyframeOfferMsg(km, *frontend.keyframeScan(step.keyframe->index), base_frame_));
  }
  closures(frontend, step);
  if (step.keyframe || !step.closures.empty()) markers(stamp);
}

void FrontendPublisher::teammateScan(frontend::RobotFrontend& frontend, const frontend::Step& step,
                                     const cosmo::Keyframe& offer) {
  if (offer.has_reference) map_.addTeammateKeyframe(offer.robot.at(0), offer.index, poseFromMsg(offer.reference));
  closures(frontend, step);
  markers(ros::Time::now());
}

void FrontendPublisher::summary(const frontend::RobotFrontend* frontend, std::uint32_t skipped,
                                std::size_t peak_waiting) const {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "frontend %c: %zu scans processed, %u skipped, at most %zu waiting; %zu keyframes, %llu measurements "
      "sent, %zu not acknowledged; peak memory %.0f MB\n",
      robot_, frontend ? frontend->scansProcessed() : 0, skipped, peak_waiting,
      frontend ? frontend->keyframes().size() : 0, static_cast<unsigned long long>(recorder_.lastSeq()),
      recorder_.unacknowledged(), usage.ru_maxrss / 1024.0);
  std::fflush(stdout);
}

void FrontendPublisher::closures(frontend::RobotFrontend& frontend, const frontend::Step& step) {
  for (const auto& pending : step.closures) {
    const frontend::LoopClosureAttempt a = frontend.complete(pending);
    if (a.accepted) {
      recorder_.send(recorderLoopClosureMsg(a, world_frame_));
      ++loop_closures_published_;
    }
    ROS_DEBUG("frontend %c: loop closure %c%zu-%c%zu %s (%zu inliers, descriptor %.3f)", robot_, a.robot1, a.index1,
              a.robot2, a.index2, a.accepted ? "accepted" : a.reason.c_str(), a.inliers, a.descriptor_distance);
    map_.addClosure(a);
  }
}

void FrontendPublisher::markers(const ros::Time& stamp) {
  marker_pub_.publish(frontendMarkers(map_, robot_, world_frame_, stamp));
}

void FrontendPublisher::ack(const frontend::RobotFrontend* frontend, StampNs stamp, std::size_t received_dropped,
                            std::size_t queued, std::uint32_t scans_skipped) {
  cosmo::FrontendAck a;
  a.header.stamp = stampToRos(stamp);
  a.header.frame_id = std::string(1, robot_);
  a.robot = a.header.frame_id;
  a.scans = static_cast<std::uint32_t>(frontend ? frontend->scansProcessed() : 0);
  a.received = static_cast<std::uint32_t>((frontend ? frontend->teammateScansReceived() : 0) + received_dropped);
  a.keyframes = static_cast<std::uint32_t>(frontend ? frontend->keyframes().size() : 0);
  a.loop_closures = static_cast<std::uint32_t>(loop_closures_published_);
  a.seq = recorder_.lastSeq();
  a.queued = static_cast<std::uint32_t>(queued);
  a.skipped = scans_skipped;
  ack_pub_.publish(a);
  ROS_INFO_THROTTLE(5.0,
                    "frontend %c: %u scans, %u keyframes, %u loop closures accepted of %zu tried, %u scans received",
                    robot_, a.scans, a.keyframes, a.loop_closures,
                    frontend ? frontend->loopClosuresAccepted() + frontend->loopClosuresRejected() : 0, a.received);
}

}  // namespace cosmo::ros_glue
