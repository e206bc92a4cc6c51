#pragma once
// A front-end's scan input in real time: a bounded queue between the subscriber (which only pushes) and the
// processing (which pops one scan at a time). When a scan arrives and `capacity` scans are waiting, the oldest
// waiting scan is skipped (dropped and counted): the front-end keeps up with the newest data, never drops the scan
// it is processing, and holds at most `capacity` scans, so its memory stays flat however far behind it falls.
// Capacity 0: unbounded, nothing is skipped (lockstep, where the player waits for every scan anyway).
// Thread-safe: push and pop may run on different threads.
#include <cstddef>
#include <algorithm>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

namespace cosmo::frontend {

template <typename T>
class ScanQueue {
 public:
  explicit ScanQueue(std::size_t capacity) : capacity_(capacity) {}

  /// Adds `scan`; returns whether a waiting scan was skipped to make room.
  bool push(T scan) {
    std::lock_guard<std::mutex> lock(mutex_);
    bool skipped = false;
    if (capacity_ > 0 && waiting_.size() >= capacity_) {
      waiting_.pop_front();
      ++skipped_;
      skipped = true;
    }
    waiting_.push_back(std::move(scan));
    peak_ = std::max(peak_, waiting_.size());
    return skipped;
  }
  /// The oldest waiting scan, if any.
  std::optional<T> pop() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (waiting_.empty()) return std::nullopt;
    T scan = std::move(waiting_.front());
    waiting_.pop_front();
    return scan;
  }
  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return waiting_.size();
  }
  /// Scans skipped so far.
  std::size_t skipped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return skipped_;
  }
  /// The most scans that waited at once.
  std::size_t peak() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return peak_;
  }
  std::size_t capacity() const { return capacity_; }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<T> waiting_;
  std::size_t skipped_ = 0, peak_ = 0;
};

}  // namespace cosmo::frontend
