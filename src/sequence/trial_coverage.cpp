#include "cosmo/sequence/trial_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace cosmo::sequence {

std::string formatStamp(StampNs stamp) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", static_cast<double>(stamp) * 1e-9);
  return buf;
}

namespace {
/// Time of the scan's first point (its stamp when it has no point times).
StampNs sweepStart(const Scan& scan) {
  if (!scan.hasTime()) return scan.stamp;
  float earliest = 0.0f;
  for (float t : scan.time)
    if (std::isfinite(t)) earliest = std::min(earliest, t);
  const long long s = static_cast<long long>(scan.stamp) + std::llround(static_cast<double>(earliest) * 1e9);
  return static_cast<StampNs>(std::max(0LL, s));
}
}  // namespace

TrialCoverage::TrialCoverage(std::string trial, Trajectory reference)
    : trial_(std::move(trial)), reference_(std::move(reference)) {}

bool TrialCoverage::before(const Scan& scan) const {
  return hasReference() && sweepStart(scan) < reference_.startStamp();
}

bool TrialCoverage::after(const Scan& scan) const { return hasReference() && scan.stamp > reference_.endStamp(); }

bool TrialCoverage::covers(const Scan& scan) const {
  if (!hasReference()) return true;
  if (before(scan) || after(scan)) return false;
  const auto& poses = reference_.poses();
  const auto hi = std::lower_bound(poses.begin(), poses.end(), scan.stamp,
                                   [](const StampedPose& p, StampNs s) { return p.stamp < s; });
  if (hi == poses.begin() || hi->stamp == scan.stamp) return true;
  return toSeconds(hi->stamp - (hi - 1)->stamp) <= kMaxReferenceGap;
}

std::string TrialCoverage::describeSpan() const {
  if (!hasReference()) return "no reference";
  const double len = toSeconds(reference_.endStamp() - reference_.startStamp());
  char buf[160];
  std::snprintf(buf, sizeof buf, "[%s, %s] (%zu poses, %.1f Hz)", formatStamp(reference_.startStamp()).c_str(),
                formatStamp(reference_.endStamp()).c_str(), reference_.size(),
                len > 0 ? static_cast<double>(reference_.size() - 1) / len : 0.0);
  return buf;
}

TrialSpan TrialCoverage::clip(const TrialSpan& scans) const {
  if (!hasReference()) return scans;
  TrialSpan out = scans;
  out.first = std::max(scans.first, reference_.startStamp());
  out.last = std::min(scans.last, reference_.endStamp());
  if (out.first > out.last)
    throw std::runtime_error("trial " + trial_ + ": the reference covers none of its scans: first uncovered stamp " +
                             formatStamp(scans.first) + ", scans [" + formatStamp(scans.first) + ", " +
                             formatStamp(scans.last) + "], reference " + describeSpan());
  return out;
}

CoveredScanSource::CoveredScanSource(std::unique_ptr<ScanSource> scans, TrialCoverage coverage, bool read_to_end)
    : scans_(std::move(scans)), coverage_(std::move(coverage)), read_to_end_(read_to_end) {}

bool CoveredScanSource::next(Scan& scan) {
  while (!ended_ && scans_->next(scan)) {
    if (coverage_.covers(scan)) {
      started_ = true;
      return true;
    }
    if (coverage_.after(scan)) {
      if (read_to_end_)
        while (scans_->next(scan)) {}
      break;
    }
    if (started_)
      throw std::runtime_error("trial " + coverage_.trial() + ": the reference does not cover the scan at " +
                               formatStamp(scan.stamp) + " (reference poses more than " +
                               formatStamp(toStampNs(kMaxReferenceGap)) + " s apart around it); reference " +
                               coverage_.describeSpan());
    ++skipped_before_;
  }
  ended_ = true;
  return false;
}

}  // namespace cosmo::sequence
