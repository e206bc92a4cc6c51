#include "cosmo/pipeline/team_radio.hpp"

#include <cmath>

namespace cosmo::pipeline {

StampNs radioGridOrigin(StampNs sequence_start, double step_s) {
  const StampNs step_ns = toStampNs(step_s);
  return step_ns > 0 ? (sequence_start / step_ns) * step_ns : sequence_start;
}

StampNs radioStepStamp(StampNs origin, double radio_time) {
  return origin + static_cast<StampNs>(std::llround(radio_time * 1e9));
}

Eigen::Vector3d radioPosition(const Trajectory& reference, StampNs step_stamp,
                              const Eigen::Vector3d& odometry_position) {
  return reference.empty() ? odometry_position : Eigen::Vector3d(reference.atClamped(step_stamp).translation());
}

StampNs nextRadioStepStamp(const comm::RadioSimulator& radio, StampNs origin) {
  const StampNs next = radioStepStamp(origin, radio.nextStepTime());
  return next > 10 ? next - 10 : 0;
}

std::size_t advanceRadio(comm::RadioSimulator& radio, StampNs origin, StampNs t, const RadioStateFn& state,
                         const RadioTransferFn& on_transfer) {
  if (t < origin) return 0;
  const double t_rel = static_cast<double>(t - origin) * 1e-9;
  std::size_t steps = 0;
  while (radio.nextStepTime() <= t_rel + 1e-9) {
    const double step_time = radio.nextStepTime();
    const StampNs step_stamp = radioStepStamp(origin, step_time);
    for (char robot : radio.robots()) {
      const RadioRobotState s = state(robot, step_stamp);
      radio.setRobotState(robot, s.position, s.on);
    }
    for (const comm::Transfer& tr : radio.step(step_time)) on_transfer(step_stamp, tr);
    ++steps;
  }
  return steps;
}

}  // namespace cosmo::pipeline
