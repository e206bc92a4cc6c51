#include "cosmo/sequence/reference_stream.hpp"

#include <algorithm>

namespace cosmo::sequence {

std::vector<StampNs> ReferenceStream::beforeScan(char robot, const Trajectory& reference, StampNs stamp) {
  if (reference.empty()) return {};
  const auto last = last_sent_.find(robot);
  const StampNs from = last != last_sent_.end() ? last->second : stamp - std::min(stamp, lead_);
  std::vector<StampNs> stamps;
  for (const auto& p : reference.poses())
    if (p.stamp > from && p.stamp < stamp && (stamps.empty() || p.stamp - stamps.back() >= spacing_))
      stamps.push_back(p.stamp);
  stamps.push_back(stamp);
  last_sent_[robot] = stamp;
  return stamps;
}

}  // namespace cosmo::sequence
