#pragma once
// Scans waiting for their reference pose. A live front-end gets its scans and its reference poses on two topics
// whose messages arrive in either order: a scan goes ahead, in arrival order, once the reference covers its stamp,
// or once a scan newer by more than `max_wait` arrived (its keyframe then has no reference pose). A front-end
// whose reference is all there from the start (lockstep: the sequence's own) waits for nothing.
#include <deque>
#include <optional>
#include <utility>

#include "cosmo/common/time.hpp"

namespace cosmo::frontend {

template <typename T>
class PendingScans {
 public:
  /// `wait_for_reference` false: every scan goes ahead at once.
  PendingScans(StampNs max_wait, bool wait_for_reference) : max_wait_(max_wait), wait_(wait_for_reference) {}

  void push(StampNs stamp, T scan) { scans_.emplace_back(stamp, std::move(scan)); }

  /// The oldest scan, when it may go ahead with the reference reaching `reference_end` (none: no reference yet).
  std::optional<T> popReady(std::optional<StampNs> reference_end) {
    if (scans_.empty() || !ready(scans_.front().first, reference_end)) return std::nullopt;
    T scan = std::move(scans_.front().second);
    scans_.pop_front();
    return scan;
  }

  std::size_t size() const { return scans_.size(); }

 private:
  bool ready(StampNs stamp, std::optional<StampNs> reference_end) const {
    if (!wait_) return true;
    const bool covered = reference_end && *reference_end >= stamp;
    const StampNs newest = scans_.back().first;
    const bool too_old = newest > stamp && newest - stamp > max_wait_;
    return covered || too_old;
  }

  StampNs max_wait_;
  bool wait_;
  std::deque<std::pair<StampNs, T>> scans_;
};

}  // namespace cosmo::frontend
