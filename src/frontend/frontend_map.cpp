#include "cosmo/frontend/frontend_map.hpp"

namespace cosmo::frontend {

FrontendMap::FrontendMap(char robot, std::optional<dataset::NoiseModels> noise)
    : robot_(robot), labeller_(std::move(noise)) {}

void FrontendMap::addKeyframe(const KeyframeRecord& kf) {
  if (trajectory_.empty() && kf.reference) world_T_odom_ = *kf.reference * kf.odom_pose.inverse();
  const Eigen::Vector3d position =
      kf.reference ? kf.reference->translation() : (world_T_odom_ * kf.odom_pose).translation();
  positions_[{robot_, kf.index}] = position;
  if (kf.reference) labeller_.addReference(robot_, kf.index, *kf.reference);
  trajectory_.push_back(position);
}

void FrontendMap::addTeammateKeyframe(char robot, std::size_t index, const Pose3& reference) {
  positions_[{robot, index}] = reference.translation();
  labeller_.addReference(robot, index, reference);
}

void FrontendMap::addClosure(const LoopClosureAttempt& a) {
  closures_.push_back({{a.robot1, a.index1}, {a.robot2, a.index2}, labeller_.label(a)});
}

std::vector<ClosureSegment> FrontendMap::closures() const {
  std::vector<ClosureSegment> segments;
  for (const Closure& c : closures_) {
    const auto a = positions_.find(c.a), b = positions_.find(c.b);
    if (a != positions_.end() && b != positions_.end()) segments.push_back({a->second, b->second, c.label});
  }
  return segments;
}

}  // namespace cosmo::frontend
