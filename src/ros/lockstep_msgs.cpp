#include "cosmo/ros/lockstep_msgs.hpp"

#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"

namespace cosmo::ros_glue {

cosmo::RadioStepRequest radioStepRequestMsg(std::uint32_t seq, StampNs through, const pipeline::RadioStepOrder& order) {
  cosmo::RadioStepRequest req;
  req.robots.assign(order.robots.begin(), order.robots.end());
  req.on.assign(order.on.begin(), order.on.end());
  req.keyframes = order.keyframes;
  req.seq = seq;
  req.stamp = stampToRos(through);
  return req;
}

pipeline::QueuedRadioStep radioStepFromMsg(const cosmo::RadioStepRequest& msg) {
  pipeline::QueuedRadioStep q;
  q.seq = msg.seq;
  q.order.through = msg.stamp.toNSec();
  q.order.robots.assign(msg.robots.begin(), msg.robots.end());
  q.order.on.assign(msg.on.begin(), msg.on.end());
  q.order.keyframes = msg.keyframes;
  return q;
}

cosmo::RadioStepDone radioStepDoneMsg(const pipeline::RadioBroker::StepDone& done) {
  cosmo::RadioStepDone msg;
  msg.seq = done.seq;
  msg.stamp = stampToRos(done.last_step);
  msg.next_stamp = stampToRos(done.next_step);
  for (const auto& [robot, n] : done.delivered) {
    msg.robots.push_back(robot);
    msg.delivered.push_back(n);
  }
  return msg;
}

std::map<char, std::uint32_t> deliveredFromMsg(const cosmo::RadioStepDone& msg) {
  std::map<char, std::uint32_t> delivered;
  for (std::size_t i = 0; i < msg.robots.size() && i < msg.delivered.size(); ++i)
    delivered[msg.robots[i]] = msg.delivered[i];
  return delivered;
}

pipeline::FrontendProgress frontendProgressFromMsg(const cosmo::FrontendAck& msg) {
  pipeline::FrontendProgress p;
  p.last_scan = msg.header.stamp.toNSec();
  p.scans = msg.scans;
  p.received = msg.received;
  p.keyframes = msg.keyframes;
  p.loop_closures = msg.loop_closures;
  p.seq = msg.seq;
  return p;
}

cosmo::Keyframe offeredKeyframeMeta(const cosmo::Keyframe& offer) {
  cosmo::Keyframe meta;
  meta.header = offer.header;
  meta.header.frame_id = offer.header.frame_id.empty() ? offer.cloud.header.frame_id : offer.header.frame_id;
  meta.index = offer.index;
  meta.reference = offer.reference;
  meta.has_reference = offer.has_reference;
  return meta;
}

cosmo::Keyframe deliveredKeyframeMsg(const cosmo::Keyframe& meta, const Scan& scan, const comm::Transfer& transfer,
                                     const ros::Time& received_at) {
  cosmo::Keyframe out;
  out.cloud = toPointCloud2(scan, meta.header.frame_id);
  out.header = meta.header;
  out.cloud.header = meta.header;
  out.robot = out.sender = std::string(1, transfer.sender);
  out.index = static_cast<std::uint32_t>(transfer.keyframe);
  out.reference = meta.reference;
  out.has_reference = meta.has_reference;
  out.received_at = received_at;
  return out;
}

}  // namespace cosmo::ros_glue
