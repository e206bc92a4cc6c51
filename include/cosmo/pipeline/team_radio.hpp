#pragma once
// Stepping the team's radio on the sequence clock, the one rule both drivers use (TeamRun offline, the
// comm_broker node in lockstep), so that they run the same steps with the same robot states:
// radio time 0 is `origin` (the sequence start rounded down to the absolute grid k * delta); advancing to t runs
// every step at a radio time <= t, each as: every robot's state is set (state(robot, step stamp)), the step
// runs, and each transfer that ended in it goes to on_transfer(step stamp, transfer), in the simulator's order,
// before the next step. The robot-state rule: on once its front-end processed a scan; position from its
// reference trajectory at the step stamp (held at the ends), else its odometry position (radioPosition).
#include <cstddef>
#include <functional>

#include <Eigen/Core>

#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/common/trajectory.hpp"

namespace cosmo::pipeline {

struct RadioRobotState {
  bool on = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

using RadioStateFn = std::function<RadioRobotState(char robot, StampNs step_stamp)>;
using RadioTransferFn = std::function<void(StampNs step_stamp, const comm::Transfer& transfer)>;

/// Radio time 0: the sequence start rounded down to the absolute grid k * step (ns).
StampNs radioGridOrigin(StampNs sequence_start, double step_s);
/// Sequence stamp of radio time `radio_time` (s since `origin`).
StampNs radioStepStamp(StampNs origin, double radio_time);
/// Position of a robot for the radio at `step_stamp`: its reference there (held at the ends), or
/// `odometry_position` without a reference.
Eigen::Vector3d radioPosition(const Trajectory& reference, StampNs step_stamp,
                              const Eigen::Vector3d& odometry_position);
/// The earliest sequence stamp at which advanceRadio runs the radio's next step: a scan stamped before it needs
/// no radio step first (LockstepSchedule). 10 ns early, under advanceRadio's 1 ns tolerance on radio time.
StampNs nextRadioStepStamp(const comm::RadioSimulator& radio, StampNs origin);
/// Runs every radio step at a time <= t (nothing before `origin`); returns the number of steps run.
std::size_t advanceRadio(comm::RadioSimulator& radio, StampNs origin, StampNs t, const RadioStateFn& state,
                         const RadioTransferFn& on_transfer);

}  // namespace cosmo::pipeline
