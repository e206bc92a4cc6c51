#include "cosmo/nebula/pose_graph_msg.hpp"

#include <cmath>
#include <stdexcept>

namespace cosmo::nebula {

std::string edgeTypeName(std::int32_t type) {
  static const char* const kNames[] = {
      "ODOM", "PRIOR", "IMU", "LOOPCLOSE", "ARTIFACT", "UWB_RANGE", "UWB_BETWEEN", "INTERROB_RANGE", "INTERROB_BETW"};
  if (type >= 0 && type <= kInterRobotBetween) return kNames[type];
  return "unknown type " + std::to_string(type);
}

Pose3 PoseMsg::toPose() const {
  for (double v : position)
    if (!std::isfinite(v)) throw std::invalid_argument("position is not finite");
  for (double v : orientation)
    if (!std::isfinite(v)) throw std::invalid_argument("orientation is not finite");
  const Eigen::Quaterniond q(orientation[3], orientation[0], orientation[1], orientation[2]);
  if (std::abs(q.norm() - 1.0) > 1e-3)
    throw std::invalid_argument("orientation is not a unit quaternion (norm " + std::to_string(q.norm()) + ")");
  return makePose(Eigen::Vector3d(position[0], position[1], position[2]), q);
}

PoseMsg PoseMsg::fromPose(const Pose3& pose) {
  const Eigen::Quaterniond q(pose.linear());
  PoseMsg m;
  m.position = {pose.translation().x(), pose.translation().y(), pose.translation().z()};
  m.orientation = {q.x(), q.y(), q.z(), q.w()};
  return m;
}

}  // namespace cosmo::nebula
