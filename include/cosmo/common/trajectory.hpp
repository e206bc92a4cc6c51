#pragma once
// A time-stamped sequence of poses (a reference trajectory or an odometry track) with interpolation.
#include <optional>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo {

struct StampedPose {
  StampNs stamp = 0;
  Pose3 pose = Pose3::Identity();
};

class Trajectory {
 public:
  Trajectory() = default;
  explicit Trajectory(std::vector<StampedPose> poses);  ///< sorts by stamp, drops duplicate stamps

  void append(StampNs stamp, const Pose3& pose);  ///< stamps must increase; an older one throws
  bool empty() const { return poses_.empty(); }
  std::size_t size() const { return poses_.size(); }
  const std::vector<StampedPose>& poses() const { return poses_; }
  StampNs startStamp() const { return poses_.front().stamp; }
  StampNs endStamp() const { return poses_.back().stamp; }
  bool covers(StampNs stamp) const { return !empty() && stamp >= startStamp() && stamp <= endStamp(); }

  /// Pose at `stamp`, interpolated; std::nullopt outside [start, end].
  std::optional<Pose3> at(StampNs stamp) const;
  /// Pose at `stamp`, interpolated, held constant before the start and after the end.
  Pose3 atClamped(StampNs stamp) const;
  /// Pose at `stamp`, interpolated, held at the nearest end for at most `tolerance` ns outside [start, end];
  /// std::nullopt farther out (and for an empty trajectory).
  std::optional<Pose3> atWithin(StampNs stamp, StampNs tolerance) const;
  /// Same trajectory with every stamp moved by `offset_ns` (may be negative).
  Trajectory shifted(long long offset_ns) const;
  /// Path length (sum of translation steps), metres.
  double length() const;

 private:
  std::vector<StampedPose> poses_;
};

}  // namespace cosmo
