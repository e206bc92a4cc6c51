// Precision / recall bookkeeping of the top candidate against reference positions.
#include <gtest/gtest.h>

#include "cosmo/place_recognition/revisit_evaluation.hpp"

namespace cosmo::place_recognition {
namespace {

QueryOutcome outcome(bool has, double distance, double match_sep, double nearest) {
  QueryOutcome o;
  o.has_candidate = has;
  o.distance = distance;
  o.match_separation = match_sep;
  o.nearest_separation = nearest;
  return o;
}

TEST(RevisitEvaluation, CountsDetectionsTruePositivesAndRevisits) {
  const std::vector<QueryOutcome> o = {
      outcome(true, 0.10, 1.0, 1.0),   // true detection
      outcome(true, 0.20, 30.0, 2.0),  // wrong place while a revisit exists
      outcome(true, 0.40, 3.0, 3.0),   // true but above 0.3
      outcome(true, 0.15, 8.0, 8.0),   // true only at 10 m
      outcome(false, 1.0, 0.0, -1.0),  // nothing searchable
  };
  const PrPoint a = precisionRecallAt(o, 0.3, 5.0);
  EXPECT_EQ(a.detections, 3u);
  EXPECT_EQ(a.true_positives, 1u);
  EXPECT_EQ(a.revisits, 3u);
  EXPECT_DOUBLE_EQ(a.precision, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(a.recall, 1.0 / 3.0);
  const PrPoint b = precisionRecallAt(o, 0.3, 10.0);
  EXPECT_EQ(b.true_positives, 2u);
  EXPECT_EQ(b.revisits, 4u);
  const PrPoint none = precisionRecallAt(o, 0.05, 5.0);
  EXPECT_EQ(none.detections, 0u);
  EXPECT_DOUBLE_EQ(none.precision, 1.0);
  EXPECT_DOUBLE_EQ(none.recall, 0.0);
  EXPECT_EQ(precisionRecall(o, {0.1, 0.2, 0.5}, 5.0).size(), 3u);
}

TEST(RevisitEvaluation, IncrementalSearchExcludesRecentEntries) {
  // Identical descriptors everywhere: the top candidate is the oldest searchable entry.
  ScanContext sc;
  sc.descriptor = Eigen::MatrixXf::Ones(20, 60);
  sc.ring_key = Eigen::VectorXf::Ones(20);
  sc.sector_key = Eigen::VectorXf::Ones(60);
  std::vector<ScanContext> d(6, sc);
  std::vector<Eigen::Vector3d> pos;
  for (int i = 0; i < 6; ++i) pos.emplace_back(2.0 * i, 0.0, 0.0);
  const auto o = evaluateIncremental(d, pos, ScanContextDatabaseParams{}, 2);
  ASSERT_EQ(o.size(), 6u);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(o[i].has_candidate);
  EXPECT_TRUE(o[3].has_candidate);
  EXPECT_EQ(o[3].match, 0u);
  EXPECT_DOUBLE_EQ(o[3].match_separation, 6.0);
  EXPECT_DOUBLE_EQ(o[5].nearest_separation, 6.0);  // entries 3 and 4 are excluded
  EXPECT_THROW(evaluateIncremental(d, {}, ScanContextDatabaseParams{}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace cosmo::place_recognition
