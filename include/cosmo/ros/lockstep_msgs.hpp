#pragma once
// The lockstep protocol's messages (player <-> comm_broker, front-ends -> player) as the core's objects
// (pipeline::LockstepSchedule, pipeline::RadioBroker), and a delivered keyframe as the receiver gets it.
#include <cstdint>
#include <map>

#include <ros/time.h>

#include "cosmo/FrontendAck.h"
#include "cosmo/Keyframe.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RadioStepRequest.h"
#include "cosmo/comm/transfer.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/pipeline/lockstep_schedule.hpp"
#include "cosmo/pipeline/radio_broker.hpp"

namespace cosmo::ros_glue {

cosmo::RadioStepRequest radioStepRequestMsg(std::uint32_t seq, StampNs through, const pipeline::RadioStepOrder& order);
pipeline::QueuedRadioStep radioStepFromMsg(const cosmo::RadioStepRequest& msg);

cosmo::RadioStepDone radioStepDoneMsg(const pipeline::RadioBroker::StepDone& done);
/// Scans delivered so far, per receiver.
std::map<char, std::uint32_t> deliveredFromMsg(const cosmo::RadioStepDone& msg);

pipeline::FrontendProgress frontendProgressFromMsg(const cosmo::FrontendAck& msg);

/// What a delivery carries besides the scan: the offer's header (frame: the cloud's when the header has none),
/// reference pose and keyframe index; no cloud.
cosmo::Keyframe offeredKeyframeMeta(const cosmo::Keyframe& offer);
/// The keyframe `transfer` delivered: `meta` (offeredKeyframeMeta) with `scan`'s x y z, its sender and the step
/// `received_at` it ended in.
cosmo::Keyframe deliveredKeyframeMsg(const cosmo::Keyframe& meta, const Scan& scan, const comm::Transfer& transfer,
                                     const ros::Time& received_at);

}  // namespace cosmo::ros_glue
