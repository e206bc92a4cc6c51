// Precision / recall of the top ScanContext candidate against reference positions.
#include "cosmo/place_recognition/revisit_evaluation.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace cosmo::place_recognition {
namespace {

double nearestAmong(const std::vector<Eigen::Vector3d>& positions, std::size_t end, const Eigen::Vector3d& p) {
  double best = -1.0;
  for (std::size_t i = 0; i < end; ++i) {
    const double d = (positions[i] - p).norm();
    if (best < 0.0 || d < best) best = d;
  }
  return best;
}

QueryOutcome outcomeOf(const std::vector<DatabaseMatch>& matches, const Eigen::Vector3d& query_position,
                       const std::vector<Eigen::Vector3d>& positions, std::size_t searchable) {
  QueryOutcome o;
  o.nearest_separation = nearestAmong(positions, searchable, query_position);
  if (!matches.empty()) {
    o.has_candidate = true;
    o.match = matches.front().id;
    o.distance = matches.front().match.distance;
    o.yaw = matches.front().match.yaw;
    o.match_separation = (positions[o.match] - query_position).norm();
  }
  return o;
}

void checkSizes(std::size_t a, std::size_t b, const char* what) {
  if (a != b)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(a) + " descriptors but " + std::to_string(b) +
                                " positions");
}

}  // namespace

std::vector<QueryOutcome> evaluateIncremental(const std::vector<ScanContext>& descriptors,
                                              const std::vector<Eigen::Vector3d>& positions,
                                              const ScanContextDatabaseParams& params, int exclude_recent) {
  checkSizes(descriptors.size(), positions.size(), "evaluateIncremental");
  ScanContextDatabase db(params);
  std::vector<QueryOutcome> out;
  const auto excluded = static_cast<std::size_t>(std::max(0, exclude_recent));
  for (std::size_t i = 0; i < descriptors.size(); ++i) {
    const std::size_t searchable = i > excluded ? i - excluded : 0;
    out.push_back(outcomeOf(db.query(descriptors[i], searchable), positions[i], positions, searchable));
    db.insert(i, descriptors[i]);
  }
  return out;
}

std::vector<QueryOutcome> evaluateAgainst(const std::vector<ScanContext>& queries,
                                          const std::vector<Eigen::Vector3d>& query_positions,
                                          const std::vector<ScanContext>& database,
                                          const std::vector<Eigen::Vector3d>& database_positions,
                                          const ScanContextDatabaseParams& params) {
  checkSizes(queries.size(), query_positions.size(), "evaluateAgainst (queries)");
  checkSizes(database.size(), database_positions.size(), "evaluateAgainst (database)");
  ScanContextDatabase db(params);
  for (std::size_t i = 0; i < database.size(); ++i) db.insert(i, database[i]);
  std::vector<QueryOutcome> out;
  for (std::size_t i = 0; i < queries.size(); ++i)
    out.push_back(outcomeOf(db.query(queries[i]), query_positions[i], database_positions, database.size()));
  return out;
}

PrPoint precisionRecallAt(const std::vector<QueryOutcome>& outcomes, double threshold, double revisit_radius) {
  PrPoint p;
  p.threshold = threshold;
  for (const QueryOutcome& o : outcomes) {
    const bool revisit = o.nearest_separation >= 0.0 && o.nearest_separation <= revisit_radius;
    if (revisit) ++p.revisits;
    if (o.has_candidate && o.distance < threshold) {
      ++p.detections;
      if (o.match_separation <= revisit_radius) ++p.true_positives;
    }
  }
  p.precision = p.detections > 0 ? static_cast<double>(p.true_positives) / static_cast<double>(p.detections) : 1.0;
  p.recall = p.revisits > 0 ? static_cast<double>(p.true_positives) / static_cast<double>(p.revisits) : 1.0;
  return p;
}

std::vector<PrPoint> precisionRecall(const std::vector<QueryOutcome>& outcomes, const std::vector<double>& thresholds,
                                     double revisit_radius) {
  std::vector<PrPoint> out;
  for (const double t : thresholds) out.push_back(precisionRecallAt(outcomes, t, revisit_radius));
  return out;
}

}  // namespace cosmo::place_recognition
