#include "cosmo/frontend/closure_label.hpp"

namespace cosmo::frontend {

ClosureLabeller::ClosureLabeller(std::optional<dataset::NoiseModels> noise, dataset::OutlierRule rule)
    : noise_(std::move(noise)), rule_(rule) {}

void ClosureLabeller::addReference(char robot, std::size_t index, const Pose3& reference) {
  references_[{robot, index}] = reference;
}

ClosureLabel ClosureLabeller::label(const LoopClosureAttempt& a) const {
  if (!a.accepted) return ClosureLabel::Rejected;
  const auto r1 = references_.find({a.robot1, a.index1});
  const auto r2 = references_.find({a.robot2, a.index2});
  if (!noise_ || r1 == references_.end() || r2 == references_.end()) return ClosureLabel::Unlabelled;
  const Pose3 truth = r1->second.inverse() * r2->second;
  return isOutlier(a.measurement, truth, noise_->loop_closure, rule_) ? ClosureLabel::Outlier : ClosureLabel::Inlier;
}

}  // namespace cosmo::frontend
