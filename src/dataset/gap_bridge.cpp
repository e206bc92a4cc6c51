#include "cosmo/dataset/gap_bridge.hpp"

#include <algorithm>
#include <cmath>

namespace cosmo::dataset {

Matrix6 unknownBridgeCovariance() {
  Matrix6 c = Matrix6::Zero();
  c.diagonal() << M_PI * M_PI, M_PI * M_PI, M_PI * M_PI, 1e6, 1e6, 1e6;
  return c;
}

GapBridge bridgeGap(StampNs before_stamp, const std::optional<Pose3>& before_reference, StampNs after_stamp,
                    const std::optional<Pose3>& after_reference, const Matrix6& odometry_covariance,
                    double keyframe_distance) {
  GapBridge b;
  b.gap_seconds = after_stamp > before_stamp ? toSeconds(after_stamp - before_stamp) : 0.0;
  if (!before_reference || !after_reference) {
    b.rule = "unknown";
    b.covariance = unknownBridgeCovariance();
    return b;
  }
  b.rule = "reference";
  b.measurement = before_reference->inverse(Eigen::Isometry) * *after_reference;
  const double distance = b.measurement.translation().norm();
  b.steps = std::max(1.0, keyframe_distance > 0 ? distance / keyframe_distance : 1.0);
  b.covariance = odometry_covariance * b.steps;
  return b;
}

}  // namespace cosmo::dataset
