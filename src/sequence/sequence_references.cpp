#include "cosmo/sequence/sequence_references.hpp"

#include <cmath>

namespace cosmo::sequence {

Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing,
                             const Eigen::Vector3d& offset) {
  std::vector<StampedPose> poses;
  poses.reserve(body_in_world.size());
  for (const auto& p : body_in_world.poses()) {
    Pose3 sensor = p.pose * extrinsic;
    sensor.translation() -= offset;
    poses.push_back({timing.toSequence(p.stamp), sensor});
  }
  return Trajectory(std::move(poses));
}

Eigen::Vector3d roundedFirstPosition(const Trajectory& anchor_reference) {
  if (anchor_reference.empty()) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d first = anchor_reference.poses().front().pose.translation();
  return Eigen::Vector3d(std::round(first.x()), std::round(first.y()), std::round(first.z()));
}

}  // namespace cosmo::sequence
