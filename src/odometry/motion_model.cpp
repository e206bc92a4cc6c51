#include "cosmo/odometry/motion_model.hpp"

#include <algorithm>

namespace cosmo::odometry {

Pose3 predictMotion(const Pose3& last_delta, double last_period, double period) {
  if (!(last_period > 0.0) || !(period > 0.0)) return last_delta;
  const double s = std::clamp(period / last_period, 0.0, 3.0);
  return expSE3(s * logSE3(last_delta));
}

}  // namespace cosmo::odometry
