// validate(): valid datasets give no violation; each broken invariant is reported with its place.
#include <gtest/gtest.h>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/synthetic.hpp"
#include "cosmo/jrl/validate.hpp"

using namespace cosmo::jrl;

namespace {

Dataset tiny() { return readJrl(std::string(COSMO_SOURCE_DIR) + "/test/jrl/data/tiny_example.jrl"); }

std::string joined(const std::vector<Violation>& v) {
  std::string s;
  for (const auto& x : v) s += x.str() + "\n";
  return s;
}

/// True when some violation's place equals `place` and its problem contains `problem`.
bool reports(const std::vector<Violation>& v, const std::string& place, const std::string& problem) {
  for (const auto& x : v)
    if (x.place == place && x.problem.find(problem) != std::string::npos) return true;
  return false;
}

Factor& factorAt(Dataset& d, char r, std::size_t e, std::size_t m) { return d.measurements.at(r)[e].factors[m]; }

}  // namespace

TEST(JrlValidate, TinyExampleIsValid) { EXPECT_TRUE(validate(tiny()).empty()) << joined(validate(tiny())); }

TEST(JrlValidate, ReferenceFileIsValid) {
  const auto path = cosmo::sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not available";
  const auto v = validate(readJrl(*path));
  EXPECT_TRUE(v.empty()) << joined(v);
}

TEST(JrlValidate, SyntheticDatasetIsValidAndDeterministic) {
  SyntheticParams p;
  p.poses_per_robot = 80;
  std::mt19937_64 rng1(7), rng2(7), rng3(8);
  const Dataset a = makeSyntheticDataset(p, rng1);
  EXPECT_TRUE(validate(a).empty()) << joined(validate(a));
  EXPECT_EQ(dumpJrl(a), dumpJrl(makeSyntheticDataset(p, rng2)));
  EXPECT_NE(dumpJrl(a), dumpJrl(makeSyntheticDataset(p, rng3)));
  EXPECT_EQ(a.measurements.at('b').size(), 80u);
  EXPECT_FALSE(a.outliers->at('a').empty() && a.outliers->at('b').empty() && a.outliers->at('c').empty());
}

TEST(JrlValidate, ReportsEachBrokenInvariantWithItsPlace) {
  Dataset d = tiny();
  // non-unit quaternion in a measurement and in ground truth
  std::get<Pose3Value>(factorAt(d, 'a', 1, 0).measured).rotation.coeffs() *= 1.01;
  std::get<Pose3Value>(d.groundtruth->at('b').at(symbol('b', 0))).rotation.coeffs() *= 0.9;
  // covariance: wrong size, asymmetric, not positive definite
  factorAt(d, 'a', 0, 0).covariance.pop_back();
  factorAt(d, 'b', 1, 1).covariance[2 * 6 + 3] = 0.001;  // (2,3) != (3,2)
  factorAt(d, 'a', 2, 1).covariance[0] = -1.0;
  // stamps decreasing
  d.measurements.at('b')[1].stamp = 5;
  // key missing from ground truth and initialization
  d.groundtruth->at('a').erase(symbol('a', 2));
  d.initialization->at('b').erase(symbol('a', 1));
  // outlier out of range, outlier not potential
  d.potential_outliers->at('b').insert(FactorId{9, 0});
  d.outliers->at('b').insert(FactorId{1, 0});
  const auto v = validate(d);
  EXPECT_TRUE(reports(v, "measurements.a[1].measurements[0].measurement.rotation", "not unit")) << joined(v);
  EXPECT_TRUE(reports(v, "groundtruth.b[1].rotation", "not unit")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.a[0].measurements[0].covariance", "expected 36 numbers, got 35")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.b[1].measurements[1].covariance", "not symmetric")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.a[2].measurements[1].covariance", "not positive definite")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.b[1].stamp", "before the previous entry")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.a[2].measurements[0].key2", "a2 is missing from groundtruth.a")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.a[2].measurements[1].key1", "a2 is missing from groundtruth.a")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.b[1].measurements[1].key2", "a1 is missing from initialization.b")) << joined(v);
  EXPECT_TRUE(reports(v, "potential_outlier_factors.b[1]", "[9,0] does not name a factor")) << joined(v);
  EXPECT_TRUE(reports(v, "outlier_factors.b[0]", "[1,0] is not listed in potential_outlier_factors.b")) << joined(v);
  EXPECT_EQ(v.size(), 11u) << joined(v);
}

TEST(JrlValidate, OdometryChainAndSharedGroundTruth) {
  Dataset d = tiny();
  // Replace a's odometry a1 -> a2 by a loop closure a0 -> a2: the chain a1 - a2 is broken.
  factorAt(d, 'a', 2, 0).keys = {symbol('a', 0), symbol('a', 2)};
  // b's copy of a1's ground truth differs from a's.
  std::get<Pose3Value>(d.groundtruth->at('b').at(symbol('a', 1))).translation.x() += 0.5;
  const auto v = validate(d);
  EXPECT_TRUE(reports(v, "measurements.a", "odometry chain broken: no Between factor a1 -> a2")) << joined(v);
  EXPECT_TRUE(reports(v, "groundtruth.b[0]", "ground truth of a1 differs from groundtruth.a")) << joined(v);
  EXPECT_EQ(v.size(), 2u) << joined(v);
}

TEST(JrlValidate, StructuralProblemsOfInMemoryDatasets) {
  Dataset d = tiny();
  factorAt(d, 'a', 1, 0).keys.pop_back();
  factorAt(d, 'b', 0, 0).measured = Scalar{1.0};
  d.measurements['z'];
  d.robots.push_back('a');
  const auto v = validate(d);
  EXPECT_TRUE(reports(v, "measurements.a[1].measurements[0]", "needs 2 key(s), has 1")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.b[0].measurements[0]", "measured value has the wrong type")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.z", "not listed in robots")) << joined(v);
  EXPECT_TRUE(reports(v, "robots[2]", "duplicate robot 'a'")) << joined(v);
}

TEST(JrlValidate, HugeKeyIndexDoesNotLoopOverTheIndexRange) {
  // A (fuzz-found) key with index near 2^56 must give one missing link, not a loop over 2^56 indices.
  Dataset d = tiny();
  factorAt(d, 'a', 2, 0).keys = {symbol('a', 1), symbol('a', kIndexMask)};
  d.groundtruth.reset();
  d.initialization.reset();
  const auto v = validate(d);
  // (consecutive referenced poses must be linked: a1 -> a72057594037927935 links a1, not a2)
  EXPECT_TRUE(reports(v, "measurements.a", "no Between factor a2 -> a72057594037927935")) << joined(v);
  EXPECT_TRUE(reports(v, "measurements.a", "no Between factor a1 -> a2")) << joined(v);
  EXPECT_EQ(v.size(), 2u) << joined(v);
}
