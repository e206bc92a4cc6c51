#include "cosmo/pipeline/sequence_references.hpp"

#include "cosmo/common/pose_io.hpp"

namespace cosmo::pipeline {

Trajectory toSensorReference(const Trajectory& body_in_world, const Pose3& extrinsic, const TrialTiming& timing) {
  std::vector<StampedPose> poses;
  poses.reserve(body_in_world.size());
  for (const auto& p : body_in_world.poses()) poses.push_back({timing.toSequence(p.stamp), p.pose * extrinsic});
  return Trajectory(std::move(poses));
}

Trajectory loadSensorReference(const TrialConfig& trial, const TrialTiming& timing) {
  if (trial.reference.empty()) return {};
  return toSensorReference(readMcdPoseCsv(trial.reference), trial.extrinsic, timing);
}

}  // namespace cosmo::pipeline
