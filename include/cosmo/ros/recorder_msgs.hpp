#pragma once
// The recorder's side of its messages: a front-end's numbered measurements (cosmo/RecorderKeyframe,
// cosmo/RecorderLoopClosure) as the core's records (dataset/measurement_record.hpp), its progress
// (cosmo/RecorderProgress) from its intake and dataset, and what a restarted front-end reads of it.
#include <string>

#include "cosmo/RecorderKeyframe.h"
#include "cosmo/RecorderLoopClosure.h"
#include "cosmo/RecorderProgress.h"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/measurement_record.hpp"
#include "cosmo/dataset/recorder_intake.hpp"
#include "cosmo/dataset/recorder_session.hpp"
#include "cosmo/live/frontend_continuation.hpp"

namespace cosmo::ros_glue {

/// The record of a message received on /<topic_robot>/keyframes_meas. Throws std::invalid_argument naming the
/// field when the robot field is not the topic's robot.
dataset::MeasurementRecord measurementFromMsg(const cosmo::RecorderKeyframe& msg, char topic_robot);
/// The record of a message received on /<topic_robot>/loop_closures (owner, robot1 and robot2 single characters).
dataset::MeasurementRecord measurementFromMsg(const cosmo::RecorderLoopClosure& msg, char topic_robot);

/// The recorder's progress: per robot what `intake` holds and where `recorder`'s chain ends.
cosmo::RecorderProgress recorderProgressMsg(const dataset::RecorderIntake& intake,
                                            const dataset::DatasetRecorder& recorder);

/// What `msg` says the recorder holds of `robot` (nothing when it does not list the robot).
live::RecorderHolding recorderHolding(const cosmo::RecorderProgress& msg, char robot);
/// The acknowledged seq of `robot` in `msg` (0 when it does not list the robot).
std::uint64_t recorderAcked(const cosmo::RecorderProgress& msg, char robot);

/// What the recorder publishes: the above for `s`, with each robot's skipped scans as its front-end last reported
/// them, the run, this recorder's `session`, why the dataset is incomplete (empty: it is not) and the last
/// `written` line.
cosmo::RecorderProgress recorderProgressMsg(const dataset::RecorderSession& s, const std::string& session,
                                            const std::string& written);

}  // namespace cosmo::ros_glue
