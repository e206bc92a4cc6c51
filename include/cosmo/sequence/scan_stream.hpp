#pragma once
// Scans of a whole team in sequence time: one ScanSource per robot (a bag reader, a folder, a synthetic
// stream in a test) merged by their synchronized stamps (SequenceTiming), ties broken by robot id. A scan whose
// stamp does not increase on its robot is dropped and counted (bad input never stops a run).
#include <cstddef>
#include <map>
#include <memory>
#include <vector>

#include "cosmo/common/scan.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::sequence {

/// One robot's scans in recorded time, in order.
class ScanSource {
 public:
  virtual ~ScanSource() = default;
  /// Next scan; false at the end.
  virtual bool next(Scan& scan) = 0;
};

/// A ScanSource over scans held in memory (tests, synthetic streams).
class VectorScanSource : public ScanSource {
 public:
  explicit VectorScanSource(std::vector<Scan> scans) : scans_(std::move(scans)) {}
  bool next(Scan& scan) override {
    if (pos_ >= scans_.size()) return false;
    scan = scans_[pos_++];
    return true;
  }

 private:
  std::vector<Scan> scans_;
  std::size_t pos_ = 0;
};

/// One robot's rule for bad input: a scan whose stamp does not increase is dropped. The merge applies it per
/// robot; a robot-side trial player (sequence/scan_read_ahead.hpp) applies it to its own trial before announcing.
class IncreasingStamps {
 public:
  /// Whether a scan stamped `stamp` is kept (then it is the latest).
  bool accept(StampNs stamp) {
    if (any_ && stamp <= last_) return false;
    any_ = true;
    last_ = stamp;
    return true;
  }

 private:
  bool any_ = false;
  StampNs last_ = 0;
};

class MergedScanStream {
 public:
  /// `sources`: robot -> its scans in recorded time; every robot needs a trial in `timing`.
  MergedScanStream(std::map<char, std::unique_ptr<ScanSource>> sources, SequenceTiming timing);
  /// Next scan of any robot in sequence time (stamp already shifted); false when every source is exhausted.
  bool next(char& robot, Scan& scan);
  /// Stamp of the next scan next() would return, or nullopt-like 0 when exhausted.
  StampNs peekStamp() const;
  const SequenceTiming& timing() const { return timing_; }
  std::size_t delivered() const { return delivered_; }
  /// Scans dropped because their stamp did not increase, per robot.
  const std::map<char, std::size_t>& dropped() const { return dropped_; }

 private:
  void refill(char robot);

  std::map<char, std::unique_ptr<ScanSource>> sources_;
  SequenceTiming timing_;
  std::map<char, Scan> pending_;  ///< the next scan of each robot that still has one (sequence time)
  std::map<char, IncreasingStamps> increasing_;
  std::map<char, std::size_t> dropped_;
  std::size_t delivered_ = 0;
};

}  // namespace cosmo::sequence
