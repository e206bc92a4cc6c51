#include "cosmo/jrl/trajectory_error.hpp"

#include <cmath>
#include <stdexcept>

namespace cosmo::jrl {

namespace {

struct SquaredSums {
  double trans = 0.0, rot = 0.0;
  std::size_t n = 0;

  void add(const cosmo::Pose3& gt, const cosmo::Pose3& est) {
    const cosmo::Pose3 E = gt.inverse() * est;
    trans += E.translation().squaredNorm();
    const double angle = cosmo::rotationAngle(E);
    rot += angle * angle;
    ++n;
  }
  PoseErrorRmse rmse() const {
    if (n == 0) return {};
    return {std::sqrt(trans / double(n)), std::sqrt(rot / double(n)), n};
  }
};

}  // namespace

TrajectoryError trajectoryError(const std::vector<char>& robots, const PoseMap& estimate, const PoseMap& groundtruth) {
  TrajectoryError out;
  SquaredSums all;
  for (char r : robots) {
    SquaredSums sums;
    for (auto it = groundtruth.lower_bound(symbol(r, 0)); it != groundtruth.end() && robotOf(it->first) == r; ++it) {
      const auto est = estimate.find(it->first);
      if (est == estimate.end()) throw std::runtime_error("no estimate of pose " + keyName(it->first));
      sums.add(it->second, est->second);
      all.add(it->second, est->second);
    }
    out.robots[r] = sums.rmse();
  }
  out.overall = all.rmse();
  return out;
}

}  // namespace cosmo::jrl
