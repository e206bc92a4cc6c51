#pragma once
// A front-end's results as the messages the recorder takes (cosmo/RecorderKeyframe, cosmo/RecorderLoopClosure),
// with the bit-exact pose fields that keep the launch's JRL byte-identical to the offline driver's, and a
// keyframe's scan as the offer to the teammates (cosmo/Keyframe, through the comm_broker).
#include <string>

#include "cosmo/Keyframe.h"
#include "cosmo/RecorderKeyframe.h"
#include "cosmo/RecorderLoopClosure.h"
#include "cosmo/frontend/robot_frontend.hpp"

namespace cosmo::ros_glue {

/// `frame`: the frame of the reference pose (the world).
cosmo::RecorderKeyframe recorderKeyframeMsg(const frontend::KeyframeRecord& keyframe, const std::string& frame);
cosmo::RecorderLoopClosure recorderLoopClosureMsg(const frontend::LoopClosureAttempt& closure,
                                                  const std::string& frame);
/// The keyframe `keyframe` (as sent to the recorder) with its scan in `scan_frame` (the robot's base frame).
cosmo::Keyframe keyframeOfferMsg(const cosmo::RecorderKeyframe& keyframe, const Scan& scan,
                                 const std::string& scan_frame);

/// A teammate's keyframe offer as delivered (cosmo/Keyframe, from the comm_broker) as the front-end's input: its
/// scan stamped with the keyframe's stamp, received at the delivery's radio step (the offline driver's time; a
/// broker without it: `now`). Throws std::runtime_error when its robot field is not one robot other than `self`.
frontend::TeammateScan teammateScanFromMsg(const cosmo::Keyframe& offer, char self, const std::string& topic,
                                           StampNs now);

}  // namespace cosmo::ros_glue
