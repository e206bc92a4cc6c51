#pragma once
// The reference poses a player sends beside a robot's scans (the /<r>/reference_pose topic): before each scan, the
// reference's own stamps since the previous scan (at most one per `spacing`; before the first scan, those of the
// `lead` before it), then the scan's stamp itself. A listener that holds the poses this way sees the reference up
// to every scan, at about the reference's rate, without a pose per reference sample.
#include <map>
#include <vector>

#include "cosmo/common/time.hpp"
#include "cosmo/common/trajectory.hpp"

namespace cosmo::sequence {

class ReferenceStream {
 public:
  explicit ReferenceStream(StampNs spacing = 20000000ULL, StampNs lead = 200000000ULL)
      : spacing_(spacing), lead_(lead) {}

  /// The stamps to send before `robot`'s scan at `stamp`, in order, ending with `stamp`; none without a reference.
  std::vector<StampNs> beforeScan(char robot, const Trajectory& reference, StampNs stamp);

 private:
  StampNs spacing_, lead_;
  std::map<char, StampNs> last_sent_;
};

}  // namespace cosmo::sequence
