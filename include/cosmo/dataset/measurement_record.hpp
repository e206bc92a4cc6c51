#pragma once
// A measurement as a front-end sends it to the recorder, numbered: one sequence number per sending robot, over
// all its measurement kinds, from 1. The numbers let the recorder drop what it already holds and acknowledge what
// it has (recorder_intake.hpp), and a front-end keep and send again what is not acknowledged (outbox.hpp).
#include <cstdint>
#include <optional>
#include <variant>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/dataset/dataset_recorder.hpp"

namespace cosmo::dataset {

/// A keyframe as its robot's front-end took it.
struct KeyframeMeasurement {
  char robot = 'a';
  std::uint32_t index = 0;
  StampNs stamp = 0;
  Pose3 odometry = Pose3::Identity();  ///< T_(index-1)^-1 * T_index (ignored for index 0 and for a bridge)
  std::optional<Pose3> reference;      ///< the reference (world) pose, when known
  /// The first keyframe of a restarted front-end: joined to keyframe *bridge_from by the bridge rule
  /// (gap_bridge.hpp), its odometry being unknown.
  std::optional<std::uint32_t> bridge_from;
  std::uint32_t scans_skipped = 0;  ///< scans the front-end skipped so far to keep up (real time)
};

struct MeasurementRecord {
  char robot = 'a';       ///< the sender
  std::uint64_t seq = 0;  ///< the sender's number, from 1
  std::variant<KeyframeMeasurement, LoopClosureMeasurement> what;

  const KeyframeMeasurement* keyframe() const { return std::get_if<KeyframeMeasurement>(&what); }
  const LoopClosureMeasurement* loopClosure() const { return std::get_if<LoopClosureMeasurement>(&what); }
};

}  // namespace cosmo::dataset
