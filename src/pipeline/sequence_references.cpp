#include "cosmo/pipeline/sequence_references.hpp"

#include <cmath>

#include "cosmo/common/pose_io.hpp"

namespace cosmo::pipeline {

Trajectory readBodyReference(const TrialConfig& trial) {
  if (trial.reference.empty()) return {};
  return readMcdPoseCsv(trial.reference);
}

TrialCoverage trialCoverage(const TrialConfig& trial) { return TrialCoverage(trial.name, readBodyReference(trial)); }

Eigen::Vector3d sequenceReferenceOffset(const SequenceConfig& config) {
  switch (config.reference_offset.mode) {
    case ReferenceOffsetConfig::Mode::None: return Eigen::Vector3d::Zero();
    case ReferenceOffsetConfig::Mode::Fixed: return config.reference_offset.fixed;
    case ReferenceOffsetConfig::Mode::Anchor: break;
  }
  const Trajectory anchor = readBodyReference(config.trial(config.anchor));
  if (anchor.empty()) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d first = anchor.poses().front().pose.translation();
  return Eigen::Vector3d(std::round(first.x()), std::round(first.y()), std::round(first.z()));
}

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

Trajectory loadSensorReference(const TrialConfig& trial, const TrialTiming& timing, const Eigen::Vector3d& offset) {
  if (trial.reference.empty()) return {};
  return toSensorReference(readBodyReference(trial), trial.extrinsic, timing, offset);
}

std::map<char, Trajectory> loadSequenceReferences(const SequenceConfig& config, const SequenceTiming& timing) {
  const Eigen::Vector3d offset = sequenceReferenceOffset(config);
  std::map<char, Trajectory> refs;
  for (const auto& t : config.trials) refs[t.robot] = loadSensorReference(t, timing.of(t.robot), offset);
  return refs;
}

}  // namespace cosmo::pipeline
