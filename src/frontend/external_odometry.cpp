#include "cosmo/frontend/external_odometry.hpp"

namespace cosmo::frontend {

void ExternalOdometry::add(StampNs stamp, const Pose3& pose) {
  poses_.emplace_back(stamp, pose);
  while (poses_.size() > capacity_) poses_.pop_front();
}

std::optional<Pose3> ExternalOdometry::at(StampNs t) const {
  if (poses_.empty()) return std::nullopt;
  for (std::size_t i = poses_.size(); i-- > 1;) {
    const auto& [t0, p0] = poses_[i - 1];
    const auto& [t1, p1] = poses_[i];
    if (t0 <= t && t <= t1) {
      const double span = static_cast<double>(t1 - t0);
      const double s = span > 0 ? static_cast<double>(t - t0) / span : 0.0;
      return interpolate(p0, p1, s);
    }
  }
  if (t >= poses_.back().first && t - poses_.back().first < hold_) return poses_.back().second;
  return std::nullopt;
}

}  // namespace cosmo::frontend
