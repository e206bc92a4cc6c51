#pragma once
// Where a front-end's numbering starts: from scratch, or, for a front-end that restarted (real time) while the
// recorder already holds measurements of its robot, after everything of the robot anyone saw:
// - its measurement numbers continue above the highest the recorder holds (what the dead process sent and the
//   recorder never got is given up: the recorder settles those numbers when the first new keyframe arrives);
// - its keyframe indices continue after the highest index of the robot the recorder saw in any measurement
//   (its keyframes, and teammates' loop closures) and the comm_broker was offered, so that no index names two poses;
// - its first keyframe is bridged from the end of the robot's recorded trajectory (gap_bridge.hpp);
// - its count of skipped scans continues from the recorder's.
#include <cstdint>
#include <optional>
#include <string>

namespace cosmo::live {

/// What the recorder holds of one robot (its /recorder/progress).
struct RecorderHolding {
  std::uint64_t highest_seq = 0;
  std::uint32_t next_index = 0;             ///< 1 + the highest keyframe index seen (0: none)
  std::optional<std::uint32_t> chain_end;   ///< the last keyframe of the robot's recorded trajectory
  std::uint32_t scans_skipped = 0;
};

struct Continuation {
  bool restart = false;
  std::uint64_t first_seq = 1;
  std::uint32_t first_index = 0;
  std::optional<std::uint32_t> bridge_from;  ///< the first keyframe joins this one
  std::uint32_t scans_skipped = 0;
  /// For the log: "starts afresh" or what it continues from.
  std::string describe() const;
};

/// `broker_next_index`: 1 + the highest index of the robot the comm_broker was offered (0: none; nullopt: not known).
Continuation continueAfter(const RecorderHolding& recorder, std::optional<std::uint32_t> broker_next_index);

}  // namespace cosmo::live
