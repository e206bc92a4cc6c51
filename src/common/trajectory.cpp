#include "cosmo/common/trajectory.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cosmo {

Trajectory::Trajectory(std::vector<StampedPose> poses) : poses_(std::move(poses)) {
  std::stable_sort(poses_.begin(), poses_.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  poses_.erase(std::unique(poses_.begin(), poses_.end(),
                           [](const StampedPose& a, const StampedPose& b) { return a.stamp == b.stamp; }),
               poses_.end());
}

void Trajectory::append(StampNs stamp, const Pose3& pose) {
  if (!poses_.empty() && stamp <= poses_.back().stamp)
    throw std::invalid_argument("Trajectory::append: stamp " + std::to_string(stamp) + " is not after the last stamp " +
                                std::to_string(poses_.back().stamp));
  poses_.push_back({stamp, pose});
}

std::optional<Pose3> Trajectory::at(StampNs stamp) const {
  if (!covers(stamp)) return std::nullopt;
  return atClamped(stamp);
}

std::optional<Pose3> Trajectory::atWithin(StampNs stamp, StampNs tolerance) const {
  if (empty()) return std::nullopt;
  if (covers(stamp)) return atClamped(stamp);
  const StampNs start = startStamp(), end = endStamp();
  if ((stamp < start && start - stamp <= tolerance) || (stamp > end && stamp - end <= tolerance))
    return atClamped(stamp);
  return std::nullopt;
}

Pose3 Trajectory::atClamped(StampNs stamp) const {
  if (poses_.empty()) throw std::logic_error("Trajectory::atClamped on an empty trajectory");
  if (stamp <= poses_.front().stamp) return poses_.front().pose;
  if (stamp >= poses_.back().stamp) return poses_.back().pose;
  const auto hi = std::lower_bound(poses_.begin(), poses_.end(), stamp,
                                   [](const StampedPose& p, StampNs s) { return p.stamp < s; });
  if (hi->stamp == stamp) return hi->pose;
  const auto lo = hi - 1;
  const double s = static_cast<double>(stamp - lo->stamp) / static_cast<double>(hi->stamp - lo->stamp);
  return interpolate(lo->pose, hi->pose, s);
}

Trajectory Trajectory::shifted(long long offset_ns) const {
  Trajectory out;
  out.poses_ = poses_;
  for (auto& p : out.poses_) p.stamp = static_cast<StampNs>(static_cast<long long>(p.stamp) + offset_ns);
  return out;
}

double Trajectory::length() const {
  double len = 0.0;
  for (std::size_t i = 1; i < poses_.size(); ++i)
    len += (poses_[i].pose.translation() - poses_[i - 1].pose.translation()).norm();
  return len;
}

}  // namespace cosmo
