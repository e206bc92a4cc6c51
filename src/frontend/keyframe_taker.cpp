#include "cosmo/frontend/keyframe_taker.hpp"

#include <vector>

#include "cosmo/odometry/dewarp.hpp"

namespace cosmo::frontend {

KeyframeTaker::KeyframeTaker(const FrontendParams& params)
    : min_range_(params.keyframe_min_range),
      dewarp_with_reference_(params.dewarp_with_reference),
      keyframer_(params.keyframe_distance) {}

odometry::KeyframeDecision KeyframeTaker::update(StampNs stamp, const Pose3& odom_pose) {
  // The odometry track for dewarping: the previous pose and this one cover the sweep.
  std::vector<StampedPose> track;
  if (!recent_odometry_.empty() && recent_odometry_.endStamp() < stamp)
    track.push_back(recent_odometry_.poses().back());
  track.push_back({stamp, odom_pose});
  recent_odometry_ = Trajectory(track);
  return keyframer_.update(odom_pose);
}

Scan KeyframeTaker::keyframeScan(const Scan& scan, const Trajectory& reference) const {
  Scan out;
  out.stamp = scan.stamp;
  const auto min_range = static_cast<float>(min_range_);
  if (!scan.hasTime()) {
    out.points = removeInvalidPoints(scan, min_range).points;
    return out;
  }
  const Trajectory& track = dewarp_with_reference_ && !reference.empty() ? reference : recent_odometry_;
  out.points =
      removeInvalidPoints(odometry::dewarp(scan, [&track](StampNs t) { return track.atClamped(t); }), min_range).points;
  return out;
}

}  // namespace cosmo::frontend
