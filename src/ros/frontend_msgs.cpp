#include "cosmo/ros/frontend_msgs.hpp"

#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"

namespace cosmo::ros_glue {

cosmo::RecorderKeyframe recorderKeyframeMsg(const frontend::KeyframeRecord& kf, const std::string& frame) {
  cosmo::RecorderKeyframe m;
  m.header.stamp = stampToRos(kf.stamp);
  m.header.frame_id = frame;
  m.robot = std::string(1, kf.robot);
  m.index = static_cast<std::uint32_t>(kf.index);
  m.odometry_from_previous = poseToMsg(kf.relative);
  m.odometry_from_previous_exact = poseToExact(kf.relative);
  m.has_reference = kf.reference.has_value();
  if (kf.reference) {
    m.reference = poseToMsg(*kf.reference);
    m.reference_exact = poseToExact(*kf.reference);
  }
  return m;
}

cosmo::RecorderLoopClosure recorderLoopClosureMsg(const frontend::LoopClosureAttempt& a, const std::string& frame) {
  cosmo::RecorderLoopClosure m;
  m.header.stamp = stampToRos(a.computed_at);
  m.header.frame_id = frame;
  m.owner = std::string(1, a.owner);
  m.robot1 = std::string(1, a.robot1);
  m.index1 = static_cast<std::uint32_t>(a.index1);
  m.robot2 = std::string(1, a.robot2);
  m.index2 = static_cast<std::uint32_t>(a.index2);
  m.measurement = poseToMsg(a.measurement);
  m.measurement_exact = poseToExact(a.measurement);
  return m;
}

frontend::TeammateScan teammateScanFromMsg(const cosmo::Keyframe& offer, char self, const std::string& topic,
                                           StampNs now) {
  if (offer.robot.size() != 1 || offer.robot[0] == self)
    throw std::runtime_error("bad robot field '" + offer.robot + "'");
  Scan scan = fromPointCloud2(offer.cloud, true, topic);
  scan.stamp = offer.header.stamp.toNSec();
  const StampNs at = offer.received_at.isZero() ? now : static_cast<StampNs>(offer.received_at.toNSec());
  return frontend::TeammateScan::decoded(offer.robot[0], offer.index, scan, at);
}

cosmo::Keyframe keyframeOfferMsg(const cosmo::RecorderKeyframe& keyframe, const Scan& scan,
                                 const std::string& scan_frame) {
  cosmo::Keyframe offer;
  offer.header.stamp = keyframe.header.stamp;
  offer.header.frame_id = scan_frame;
  offer.robot = keyframe.robot;
  offer.index = keyframe.index;
  offer.cloud = toPointCloud2(scan, scan_frame);
  offer.reference = keyframe.reference;
  offer.has_reference = keyframe.has_reference;
  return offer;
}

}  // namespace cosmo::ros_glue
