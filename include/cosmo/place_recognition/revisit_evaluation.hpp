#pragma once
// Precision / recall of place recognition against reference positions (used by cosmo_scancontext and
// bench_scancontext). For each query the top candidate of the two-phase search is kept with its descriptor
// distance. At a threshold t and revisit radius R:
//   detection       = the query has a candidate with distance < t
//   true positive   = a detection whose matched reference position is within R of the query's
//   revisit (positive) = some searchable entry lies within R of the query
//   precision = TP / detections, recall = TP / revisits (1 when there is nothing to count).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "cosmo/place_recognition/scan_context_database.hpp"

namespace cosmo::place_recognition {

struct QueryOutcome {
  bool has_candidate = false;
  std::size_t match = 0;             ///< index (into the searched list) of the top candidate
  double distance = 1.0;             ///< its descriptor distance
  double yaw = 0.0;                  ///< its yaw estimate
  double match_separation = 0.0;     ///< reference distance query <-> top candidate, m
  double nearest_separation = -1.0;  ///< reference distance to the nearest searchable entry, m (-1: none)
};

struct PrPoint {
  double threshold = 0.0;
  std::size_t detections = 0, true_positives = 0, revisits = 0;
  double precision = 1.0, recall = 1.0;
};

/// Each descriptor searched against the earlier ones except the `exclude_recent` most recent, then inserted.
std::vector<QueryOutcome> evaluateIncremental(const std::vector<ScanContext>& descriptors,
                                              const std::vector<Eigen::Vector3d>& positions,
                                              const ScanContextDatabaseParams& params, int exclude_recent);
/// Each query searched against a database holding all of `database` (inter-robot use).
std::vector<QueryOutcome> evaluateAgainst(const std::vector<ScanContext>& queries,
                                          const std::vector<Eigen::Vector3d>& query_positions,
                                          const std::vector<ScanContext>& database,
                                          const std::vector<Eigen::Vector3d>& database_positions,
                                          const ScanContextDatabaseParams& params);
PrPoint precisionRecallAt(const std::vector<QueryOutcome>& outcomes, double threshold, double revisit_radius);
std::vector<PrPoint> precisionRecall(const std::vector<QueryOutcome>& outcomes, const std::vector<double>& thresholds,
                                     double revisit_radius);

}  // namespace cosmo::place_recognition
