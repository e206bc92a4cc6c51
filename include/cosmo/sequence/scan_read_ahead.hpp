#pragma once
// Robot-side playback (sequence.launch playback:=robot): each robot's trial is read on the robot's own machine by
// a trial player, and the base's player, which holds no scan, decides the team's order as it always does
// (MergedScanStream over the robots' stamps, then LockstepSchedule) and asks each robot for its scans one by one.
// The two ends of that exchange, without ROS:
// - ScanReadAhead (robot side): the scans read and not played yet, at most `capacity`; their stamps are announced
//   (the whole window, after every read, so that a late or lost message costs nothing); the base asks for a scan by
//   its stamp and the scans before it are dropped.
// - AnnouncedStamps (base side): one robot's announced windows as a stream of stamps in order, which the merge
//   reads as it would read the scans themselves.
// Stamps are the trial's recorded sweep-end stamps; a scan whose stamp does not increase is dropped on the robot
// side by the merge's own rule (IncreasingStamps), so the order is the one a base reading every bag makes.
#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/sequence/scan_stream.hpp"

namespace cosmo::sequence {

class ScanReadAhead {
 public:
  explicit ScanReadAhead(std::size_t capacity);

  /// More scans should be read: not at the trial's end and fewer than `capacity` held.
  bool wantsMore() const { return !ended_ && held_.size() < capacity_; }
  /// A scan read from the trial, in order. False when it is dropped (its stamp does not increase).
  bool add(Scan scan);
  /// The trial has no more scans.
  void endOfTrial() { ended_ = true; }

  /// The stamps of the scans held, in order (the announcement), and whether the trial has no more after them.
  std::vector<StampNs> stamps() const;
  bool ended() const { return ended_; }

  /// Drops the scans held stamped before `stamp` (the base's merge passed them over). True when a scan stamped
  /// `stamp` or later is held; false: read on (add() takes scans beyond the capacity then: a trial player that
  /// restarted reads forward to where the base is).
  bool passOver(StampNs stamp);
  /// The scan stamped `stamp`, after passOver(stamp). Throws std::runtime_error naming the stamp and the stamps
  /// held when it holds none stamped so.
  Scan take(StampNs stamp);

  std::size_t dropped() const { return dropped_; }  ///< stamps that did not increase
  std::size_t skipped() const { return skipped_; }  ///< held scans passed over (passOver, take)

 private:
  std::size_t capacity_;
  std::deque<Scan> held_;
  sequence::IncreasingStamps increasing_;
  bool ended_ = false;
  std::size_t dropped_ = 0, skipped_ = 0;
};

class AnnouncedStamps {
 public:
  /// One announcement: the stamps of the scans read and not played (increasing), and whether the trial ends after
  /// them. Stamps already known are skipped; a window whose stamps do not increase, or that leaves out a stamp
  /// announced before and not taken yet, throws std::runtime_error saying so.
  void announce(const std::vector<StampNs>& window, bool end);
  /// The next stamp, taken; nullopt while it is not announced yet (or after the end: exhausted()).
  std::optional<StampNs> take();
  /// The end was announced and every stamp taken.
  bool exhausted() const { return end_ && pending_.empty(); }
  /// Something was announced.
  bool heard() const { return heard_; }
  std::size_t taken() const { return taken_; }

 private:
  std::deque<StampNs> pending_;  ///< announced, not taken
  std::optional<StampNs> last_;  ///< the latest stamp known (taken or pending)
  bool end_ = false, heard_ = false;
  std::size_t taken_ = 0;
};

}  // namespace cosmo::sequence
