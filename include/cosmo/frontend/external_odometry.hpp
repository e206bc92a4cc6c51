#pragma once
// Odometry from another source (a robot's own odometry topic), kept for the scans that take their pose from it:
// the latest poses, interpolated at a scan's stamp, the newest held a short while past its stamp.
#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::frontend {

class ExternalOdometry {
 public:
  /// Keeps the latest `capacity` poses; the newest holds for `hold` ns after its stamp.
  explicit ExternalOdometry(std::size_t capacity = 2000, StampNs hold = 200000000ULL)
      : capacity_(capacity), hold_(hold) {}

  void add(StampNs stamp, const Pose3& pose);
  /// The pose at `t`: interpolated between the two poses around it, the newest within `hold` after it; none
  /// before the first pose kept, or later than that.
  std::optional<Pose3> at(StampNs t) const;

 private:
  std::size_t capacity_;
  StampNs hold_;
  std::deque<std::pair<StampNs, Pose3>> poses_;
};

}  // namespace cosmo::frontend
