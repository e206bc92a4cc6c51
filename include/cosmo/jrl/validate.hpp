#pragma once
// Invariants a back-end relies on (issue 2, jrl.md §10/§14), checked on a Dataset in memory. Every violation is
// reported with its place in the JSON layout, e.g. "measurements.b[12].measurements[1].covariance".
#include <string>
#include <vector>

#include "cosmo/jrl/dataset.hpp"

namespace cosmo::jrl {

struct Violation {
  std::string place;    ///< JSON path ("measurements.a[3].measurements[0].key2", "outlier_factors.b[4]", ...)
  std::string problem;  ///< what is wrong
  std::string str() const { return place.empty() ? problem : place + ": " + problem; }
};

/// Checked: robot ids printable and unique, no per-robot data for unlisted robots; per factor the key count,
/// measured type, unit quaternions / Unit3 (kUnitNormTolerance), covariance of d*d finite numbers that is
/// symmetric (|Σij-Σji| <= 1e-9·max|Σ|) and positive definite (Cholesky); per robot stamps non-decreasing;
/// every key a robot's factors reference present in that robot's groundtruth and initialization (when the
/// dataset has them); finite values with unit quaternions; ground truth of a key shared by several robots
/// identical (1e-9); outlier ids in range and outliers ⊆ potential outliers; odometry chain unbroken (every own
/// pose r<i>, i > 0, that robot r's Pose2/Pose3 factors reference is linked to r<i-1> by a Between factor in r's
/// list, so poses 0..N form one chain; at most 20 missing links are listed per robot).
/// Cost: O(factors · log) whatever the key values (no loop over index ranges).
/// Returns every violation, in document order; empty = valid.
std::vector<Violation> validate(const Dataset& dataset);

}  // namespace cosmo::jrl
