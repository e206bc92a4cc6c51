#include "cosmo/pipeline/sequence_references.hpp"

namespace cosmo::pipeline {

Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing) {
  std::vector<StampedPose> poses;
  poses.reserve(body_in_world.size());
  for (const auto& p : body_in_world.poses()) poses.push_back({timing.toSequence(p.stamp), p.pose * extrinsic});
  return Trajectory(std::move(poses));
}

}  // namespace cosmo::pipeline
