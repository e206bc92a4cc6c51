#include "cosmo/sequence/trial_basis.hpp"

#include <stdexcept>
#include <string>

#include "cosmo/sequence/sequence_references.hpp"

namespace cosmo::sequence {

namespace {

const TrialBasis& basisOf(const std::map<char, TrialBasis>& trials, char robot) {
  const auto it = trials.find(robot);
  if (it == trials.end())
    throw std::runtime_error(std::string("robot ") + robot + ": no span and reference for its trial");
  return it->second;
}

}  // namespace

Eigen::Vector3d referenceOffset(const ReferenceOffsetConfig& offset, const Trajectory& anchor_body_reference) {
  switch (offset.mode) {
    case ReferenceOffsetConfig::Mode::None: return Eigen::Vector3d::Zero();
    case ReferenceOffsetConfig::Mode::Fixed: return offset.fixed;
    case ReferenceOffsetConfig::Mode::Anchor: break;
  }
  return roundedFirstPosition(anchor_body_reference);
}

SequenceTiming synchronizeTrials(const SequenceConfig& config, const std::map<char, TrialBasis>& trials) {
  std::vector<TrialSpan> spans;
  for (const auto& t : config.trials) {
    TrialSpan span = basisOf(trials, t.robot).span;
    span.robot = t.robot;
    spans.push_back(span);
  }
  return SequenceTiming::synchronize(spans, config.anchor, config.time_offset_sigma, config.seed);
}

std::map<char, Trajectory> sensorReferences(const SequenceConfig& config, const std::map<char, TrialBasis>& trials,
                                            const SequenceTiming& timing) {
  const bool by_anchor = config.reference_offset.mode == ReferenceOffsetConfig::Mode::Anchor;
  const Eigen::Vector3d offset =
      referenceOffset(config.reference_offset, by_anchor ? basisOf(trials, config.anchor).body_reference : Trajectory());
  std::map<char, Trajectory> refs;
  for (const auto& t : config.trials) {
    const Trajectory& body = basisOf(trials, t.robot).body_reference;
    refs[t.robot] = body.empty() ? Trajectory() : toSensorReference(body, t.extrinsic, timing.of(t.robot), offset);
  }
  return refs;
}

}  // namespace cosmo::sequence
