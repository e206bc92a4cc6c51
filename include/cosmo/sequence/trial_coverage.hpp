#pragma once
// Which of a trial's scans the pipeline uses: those its reference covers.
//
// Scans arrive stamped at their sweep end, point times <= 0 (the decode applies the trial's `stamp: start | end`,
// trials/point_cloud_decode.hpp). A trial's reference is valid over its own span, [first pose, last pose]. A scan
// is covered when its whole sweep lies inside it (first point at or after the first pose, sweep end at or before
// the last) and the reference poses around its sweep end are at most kMaxReferenceGap apart. The robot is off
// until its first covered scan (scans before it are skipped) and its trial ends at its last one (scans after the
// reference's end are not read), so every keyframe it writes has a groundtruth pose. An uncovered scan inside the
// span after a covered one (a gap in the reference) stops the run: std::runtime_error naming the trial, the stamp
// and the span.
#include <memory>
#include <string>

#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::sequence {

/// Largest spacing of the reference poses around a covered sweep end (s).
inline constexpr double kMaxReferenceGap = 1.0;

/// "<seconds since the epoch, 3 decimals>" for messages.
std::string formatStamp(StampNs stamp);

/// Which scans of a trial have a reference pose (see the file comment). An empty reference covers every scan.
class TrialCoverage {
 public:
  TrialCoverage() = default;
  /// `reference`: the trial's reference in its recorded time (any frame); `trial`: its name for messages.
  TrialCoverage(std::string trial, Trajectory reference);

  bool hasReference() const { return !reference_.empty(); }
  /// The scan (stamped at its sweep end, recorded time) lies inside the span with no gap at its end.
  bool covers(const Scan& scan) const;
  /// Before the reference's first pose (the robot is still off) / after its last (the trial is over).
  bool before(const Scan& scan) const;
  bool after(const Scan& scan) const;
  /// Scan span clipped to the reference span (recorded time). Throws naming the trial, the first uncovered stamp
  /// and both spans when they do not overlap.
  TrialSpan clip(const TrialSpan& scans) const;
  /// "[first, last] (N poses, R Hz)" of the reference.
  std::string describeSpan() const;
  const std::string& trial() const { return trial_; }
  const Trajectory& reference() const { return reference_; }

 private:
  std::string trial_;
  Trajectory reference_;
};

/// A trial's scans in recorded time, only the covered ones (see the file comment). With `read_to_end`, the scans
/// after the reference's span are still read (and dropped) when the first of them is met, so that a source that
/// keeps what it reads (the scan cache of a compressed bag, trials/scan_cache.hpp) sees the whole trial.
class CoveredScanSource : public ScanSource {
 public:
  CoveredScanSource(std::unique_ptr<ScanSource> scans, TrialCoverage coverage, bool read_to_end = false);
  bool next(Scan& scan) override;
  std::size_t skippedBefore() const { return skipped_before_; }

 private:
  std::unique_ptr<ScanSource> scans_;
  TrialCoverage coverage_;
  bool read_to_end_ = false, started_ = false, ended_ = false;
  std::size_t skipped_before_ = 0;
};

}  // namespace cosmo::sequence
