// ScanContext database and PlaceRecognizer: near-duplicate retrieval, exclusion of recent entries, entries
// newer than the last k-d tree rebuild, intra- and inter-robot candidates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/place_recognition/scan_context_database.hpp"
#include "cosmo/test_support/sim_scenes.hpp"

namespace cosmo::place_recognition {
namespace {

const sim::World& scene() {
  static const sim::World s = test_support::pillarWorld(11);
  return s;
}

/// Poses along a lawnmower path through the scene, 6 m apart (x, y, yaw).
std::vector<Eigen::Vector3d> path(int n) {
  std::vector<Eigen::Vector3d> poses;
  for (int i = 0; i < n; ++i) {
    const int row = i / 25, col = i % 25;
    const double x = -150.0 + 12.0 * (row % 2 == 0 ? col : 24 - col);
    poses.emplace_back(x, -150.0 + 40.0 * row, 0.1 * i);
  }
  return poses;
}

Scan noisy(const Scan& scan, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> n(0.0f, 0.05f);
  Scan out = scan;
  for (auto& p : out.points) p += Eigen::Vector3f(n(rng), n(rng), n(rng));
  return out;
}

TEST(ScanContextDatabase, FindsTheInsertedNearDuplicateAndRespectsTheSearchLimit) {
  const ScanContextParams sc;
  ScanContextDatabaseParams dp;
  dp.rebuild_every = 16;
  ScanContextDatabase db(dp);
  const auto poses = path(100);
  for (std::size_t i = 0; i < poses.size(); ++i)
    db.insert(1000 + i, makeScanContext(test_support::scanAt(scene(), poses[i].x(), poses[i].y(), poses[i].z()), sc),
              i);
  EXPECT_EQ(db.size(), 100u);
  EXPECT_EQ(db.indexedSize(), 96u);
  for (std::size_t i : {3u, 40u, 77u, 98u}) {
    // The same place seen 0.5 m away, turned by 40 degrees, with noise.
    const Scan q = noisy(test_support::scanAt(scene(), poses[i].x() + 0.4, poses[i].y() - 0.3, poses[i].z() + 0.7), i);
    const auto matches = db.query(makeScanContext(q, sc));
    ASSERT_FALSE(matches.empty());
    EXPECT_EQ(matches.front().id, 1000 + i);
    EXPECT_EQ(matches.front().position, i);
    EXPECT_LT(matches.front().match.distance, 0.3);
    EXPECT_LE(std::abs(std::remainder(matches.front().match.yaw - 0.7, 2.0 * M_PI)), 2.0 * M_PI / 60.0);
    for (std::size_t k = 1; k < matches.size(); ++k)
      EXPECT_LE(matches[k - 1].match.distance, matches[k].match.distance);
    // Limited to the entries before it, the near-duplicate is never returned.
    for (const auto& m : db.query(makeScanContext(q, sc), i)) EXPECT_LT(m.position, i);
  }
  EXPECT_TRUE(db.query(makeScanContext(test_support::scanAt(scene(), 0, 0, 0), sc), 0).empty());
}

TEST(ScanContextDatabase, QueriesSeeEntriesInsertedAfterTheLastRebuild) {
  const ScanContextParams sc;
  ScanContextDatabaseParams dp;
  dp.rebuild_every = 50;
  ScanContextDatabase db(dp);
  const auto poses = path(60);
  std::vector<ScanContext> descriptors;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    descriptors.push_back(makeScanContext(test_support::scanAt(scene(), poses[i].x(), poses[i].y(), poses[i].z()), sc));
    db.insert(i, descriptors.back());
    // Right after insertion the entry is found, whether or not the tree holds it.
    const auto m = db.query(descriptors.back());
    ASSERT_FALSE(m.empty());
    EXPECT_EQ(m.front().id, i);
    EXPECT_NEAR(m.front().match.distance, 0.0, 1e-6);
  }
  EXPECT_EQ(db.indexedSize(), 50u);
  EXPECT_EQ(db.query(descriptors[57]).front().id, 57u);
  EXPECT_EQ(db.nearestRingKeys(descriptors[57].ring_key, 1).front(), 57u);
  EXPECT_EQ(db.query(descriptors[5]).front().id, 5u);
  // Different descriptor sizes are refused.
  ScanContextParams small;
  small.rings = 10;
  EXPECT_THROW(db.insert(99, makeScanContext(test_support::scanAt(scene(), 0, 0, 0), small)), std::invalid_argument);
}

TEST(PlaceRecognizer, IntraRobotRevisitAndRecentExclusion) {
  PlaceRecognitionParams p;
  p.exclude_recent = 5;
  PlaceRecognizer rec('a', p);
  const auto poses = path(40);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    // Consecutive keyframes 6 m apart still look alike: with exclusion they must not be reported.
    const auto c = rec.addOwnKeyframe(i, test_support::scanAt(scene(), poses[i].x(), poses[i].y(), poses[i].z()));
    for (const auto& lc : c) EXPECT_LE(lc.match_index + 5, i) << "recent keyframe " << lc.match_index;
  }
  // Revisit keyframe 12 (a 0.5 m offset, turned around).
  const auto c =
      rec.addOwnKeyframe(40, noisy(test_support::scanAt(scene(), poses[12].x() + 0.5, poses[12].y(), 2.5), 3));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].query_robot, 'a');
  EXPECT_EQ(c[0].match_robot, 'a');
  EXPECT_EQ(c[0].query_index, 40u);
  EXPECT_EQ(c[0].match_index, 12u);
  EXPECT_LT(c[0].distance, p.threshold);
  EXPECT_LE(std::abs(std::remainder(c[0].yaw - (2.5 - poses[12].z()), 2.0 * M_PI)), 2.0 * M_PI / 60.0);
  // A scan of keyframe 39 again: excluded as recent (39 is within the last 5 of 41 entries).
  for (const auto& lc :
       rec.addOwnKeyframe(41, test_support::scanAt(scene(), poses[39].x(), poses[39].y(), poses[39].z())))
    EXPECT_NE(lc.match_index, 39u);
}

TEST(PlaceRecognizer, TimeBasedExclusion) {
  PlaceRecognitionParams p;
  p.exclude_recent = 0;
  p.exclude_recent_seconds = 10.0;
  PlaceRecognizer rec('a', p);
  Scan s = test_support::scanAt(scene(), 0, 0, 0);
  s.stamp = 100'000'000'000ULL;
  EXPECT_TRUE(rec.addOwnKeyframe(0, s).empty());
  s.stamp += 5'000'000'000ULL;  // 5 s later, same place: excluded
  EXPECT_TRUE(rec.addOwnKeyframe(1, s).empty());
  s.stamp += 20'000'000'000ULL;  // 25 s after keyframe 0: both earlier ones are searchable
  const auto c = rec.addOwnKeyframe(2, s);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].match_index, 0u);  // equal distances: the older entry first
}

TEST(PlaceRecognizer, InterRobotSearchBothWays) {
  PlaceRecognitionParams p;
  p.threshold = 0.35;  // the toy scene's pillars change faster with a 0.5 m offset than real scenes
  PlaceRecognizer rec('b', p);
  const auto poses = path(30);
  for (std::size_t i = 0; i < 20; ++i)
    EXPECT_TRUE(rec.addOwnKeyframe(i, test_support::scanAt(scene(), poses[i].x(), poses[i].y(), poses[i].z())).empty());
  // A scan from robot a at b's keyframe 7: matched against b's own database (no exclusion).
  auto c = rec.addTeammateScan('a', 3, noisy(test_support::scanAt(scene(), poses[7].x(), poses[7].y() + 0.5, -1.0), 1));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].query_robot, 'a');
  EXPECT_EQ(c[0].query_index, 3u);
  EXPECT_EQ(c[0].match_robot, 'b');
  EXPECT_EQ(c[0].match_index, 7u);
  // A scan from robot c at a new place: nothing; stored in c's database.
  EXPECT_TRUE(rec.addTeammateScan('c', 9, test_support::scanAt(scene(), poses[25].x(), poses[25].y(), 0.0)).empty());
  ASSERT_NE(rec.teammateDatabase('c'), nullptr);
  EXPECT_EQ(rec.teammateDatabase('c')->size(), 1u);
  EXPECT_EQ(rec.teammateDatabase('z'), nullptr);
  // b reaches that place: matched in c's database (and not in its own).
  c = rec.addOwnKeyframe(20, noisy(test_support::scanAt(scene(), poses[25].x() - 0.5, poses[25].y(), 1.5), 2));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].query_robot, 'b');
  EXPECT_EQ(c[0].query_index, 20u);
  EXPECT_EQ(c[0].match_robot, 'c');
  EXPECT_EQ(c[0].match_index, 9u);
  EXPECT_LE(std::abs(std::remainder(c[0].yaw - 1.5, 2.0 * M_PI)), 2.0 * M_PI / 60.0);
  // The same teammate scan twice is stored once; the own id is refused.
  rec.addTeammateScan('c', 9, test_support::scanAt(scene(), poses[25].x(), poses[25].y(), 0.0));
  EXPECT_EQ(rec.teammateDatabase('c')->size(), 1u);
  EXPECT_THROW(rec.addTeammateScan('b', 0, Scan{}), std::invalid_argument);
  // Empty scans do not crash and match nothing.
  EXPECT_TRUE(rec.addTeammateScan('a', 4, Scan{}).empty());
  EXPECT_TRUE(rec.addOwnKeyframe(21, Scan{}).empty());
}

// The shipped file against the defaults: test/pipeline/test_parameter_lists.cpp (every listed parameter).
TEST(PlaceRecognizer, ParamsFromConfigRefuseANegativeCandidateCount) {
  ConfigNode bad;
  bad.node = YAML::Load("place_recognition: {num_candidates: -3}");
  bad.where = "test.yaml: ";
  EXPECT_THROW(PlaceRecognitionParams::fromConfig(bad), std::runtime_error);
}

}  // namespace
}  // namespace cosmo::place_recognition
