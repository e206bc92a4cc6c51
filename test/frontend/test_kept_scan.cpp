// The keyframe store's memory: the spill file returns exactly what was written, a kept scan and its features come
// back bit for bit once nobody holds them, a front-end keeps in memory only its latest keyframe scan whatever the
// number of keyframes, and a team run writes the same JRL bytes with and without spilling.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <stdexcept>

#include "cosmo/frontend/feature_cache.hpp"
#include "cosmo/frontend/kept_scan.hpp"
#include "cosmo/frontend/robot_frontend.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/seed_streams.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/frontend/spill_file.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/registration/global_registration.hpp"
#include "../support/synthetic_team.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using namespace cosmo::frontend;
using namespace cosmo::sequence;

namespace {

const std::vector<test::SyntheticTrial>& team() { return test::sharedSyntheticTeam(2, 60); }

Trajectory sensorReference(const test::SyntheticTrial& t) {
  TrialTiming identity;
  identity.robot = t.robot;
  return toSensorReference(t.body, t.extrinsic, identity);
}

bool sameBits(const void* a, const void* b, std::size_t n) { return n == 0 || std::memcmp(a, b, n) == 0; }

template <typename T>
bool sameArray(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && sameBits(a.data(), b.data(), sizeof(T) * a.size());
}

}  // namespace

TEST(SpillFile, ReadsBackExactlyWhatWasWrittenAndNamesAMissingFolder) {
  SpillFile spill;
  std::vector<std::vector<char>> blocks;
  std::vector<SpillFile::Extent> extents;
  for (int i = 0; i < 5; ++i) {
    std::vector<char> b(1000 * i + 7);
    for (std::size_t k = 0; k < b.size(); ++k) b[k] = static_cast<char>((k * 31 + i) & 0xff);
    extents.push_back(spill.append(b.data(), b.size()));
    blocks.push_back(std::move(b));
  }
  std::uint64_t total = 0;
  for (const auto& b : blocks) total += b.size();
  EXPECT_EQ(spill.size(), total);
  for (int i = 4; i >= 0; --i) {
    std::vector<char> back(extents[i].size);
    spill.read(extents[i], back.data());
    EXPECT_EQ(back, blocks[i]) << i;
  }
  try {
    SpillFile bad("/nonexistent/cosmo_spill_dir");
    FAIL() << "no error for a missing folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/cosmo_spill_dir"), std::string::npos) << e.what();
  }
}

TEST(KeptScan, ComesBackBitForBitOnceReleasedAndHoldsNoPointsMeanwhile) {
  auto spill = std::make_shared<SpillFile>();
  Scan original = team()[0].scans[3];  // points, intensity, time, ring
  ASSERT_TRUE(original.hasTime());
  original.points[0].x() = -0.0f;  // bit patterns, not values, must survive
  const std::size_t bytes = scanBytes(original);
  auto held = std::make_shared<const Scan>(original);
  KeptScan kept(held, spill);
  EXPECT_TRUE(kept.spilled());
  EXPECT_EQ(kept.bytes(), bytes);
  EXPECT_EQ(kept.bytesInMemory(), bytes);   // its producer still holds it
  EXPECT_EQ(kept.get().get(), held.get());  // in use: the same object, not a copy
  held.reset();
  EXPECT_EQ(kept.bytesInMemory(), 0u);  // released: only the file has it
  const std::shared_ptr<const Scan> back = kept.get();
  EXPECT_EQ(back->stamp, original.stamp);
  EXPECT_TRUE(sameArray(back->points, original.points));
  EXPECT_TRUE(sameArray(back->intensity, original.intensity));
  EXPECT_TRUE(sameArray(back->time, original.time));
  EXPECT_TRUE(sameArray(back->ring, original.ring));
  EXPECT_EQ(kept.get().get(), back.get());  // read once while in use
  // without a spill file it is held
  KeptScan in_memory(std::make_shared<const Scan>(original), nullptr);
  EXPECT_FALSE(in_memory.spilled());
  EXPECT_EQ(in_memory.bytesInMemory(), bytes);
}

TEST(FeatureCache, SpilledFeaturesComeBackBitForBitAndLeaveMemory) {
  const registration::GlobalRegistration registration(FrontendParams::loadDir(defaultConfigDir()).registration);
  auto spill = std::make_shared<SpillFile>();
  FeatureCache cache(spill);
  auto scan = std::make_shared<const KeptScan>(std::make_shared<const Scan>(team()[0].scans[0]), spill);
  int computed = 0;
  const auto prepare = [&](const Scan& s) {
    ++computed;
    return registration.prepare(s);
  };
  const registration::FeatureCloud direct = registration.prepare(*scan->get());
  ASSERT_GT(direct.keypoints.size(), 10u);
  std::shared_ptr<const registration::FeatureCloud> first = cache.get(scan, prepare);
  EXPECT_EQ(cache.footprint().bytes_in_memory, featureCloudBytes(direct));
  EXPECT_EQ(cache.get(scan, prepare).get(), first.get());  // in use: the same object
  first.reset();
  EXPECT_EQ(cache.footprint().bytes_in_memory, 0u);
  EXPECT_EQ(cache.footprint().bytes_spilled, featureCloudBytes(direct));
  const std::shared_ptr<const registration::FeatureCloud> back = cache.get(scan, prepare);
  EXPECT_EQ(computed, 1);  // read back, not recomputed
  EXPECT_TRUE(sameArray(back->points, direct.points));
  EXPECT_TRUE(sameArray(back->normals, direct.normals));
  EXPECT_TRUE(sameArray(back->keypoints, direct.keypoints));
  ASSERT_EQ(back->features.cols(), direct.features.cols());
  EXPECT_TRUE(sameBits(back->features.data(), direct.features.data(), sizeof(float) * direct.features.size()));
  EXPECT_EQ(back->input_points, direct.input_points);
  EXPECT_EQ(back->downsampled_points, direct.downsampled_points);
}

TEST(RobotFrontend, KeepsOnlyTheLatestKeyframeScanInMemoryWithTheSameClosures) {
  const auto& a = team()[0];
  const auto& b = team()[1];
  FrontendParams spilled = FrontendParams::loadDir(defaultConfigDir());
  spilled.place.exclude_recent = 5;
  spilled.odometry = OdometryKind::Reference;
  FrontendParams in_memory = spilled;
  in_memory.spill_keyframes = false;
  RobotFrontend fa('a', spilled, sensorReference(a)), fb('b', spilled, sensorReference(b));
  RobotFrontend ma('a', in_memory, sensorReference(a)), mb('b', in_memory, sensorReference(b));
  std::size_t largest = 0;
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    for (RobotFrontend* f : {&fa, &ma}) f->add(OwnScan::of(a.scans[i]));
    for (RobotFrontend* f : {&fb, &mb}) f->add(OwnScan::of(b.scans[i]));
  }
  ASSERT_GE(fa.keyframes().size(), 4u);
  for (std::size_t k = 0; k < fa.keyframes().size(); ++k) largest = std::max(largest, fa.keptScan(k)->bytes());
  // b receives every keyframe of a: the same attempts, bit for bit, from the spilled and the in-memory stores
  std::size_t attempts = 0;
  for (std::size_t k = 0; k < fa.keyframes().size(); ++k) {
    const auto s = fb.add(TeammateScan::keptBySender('a', k, fa.keptScan(k), 1000 + k)).closures;
    const auto m = mb.add(TeammateScan::keptBySender('a', k, ma.keptScan(k), 1000 + k)).closures;
    ASSERT_EQ(s.size(), m.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      const LoopClosureAttempt x = fb.complete(s[i]), y = mb.complete(m[i]);
      EXPECT_EQ(x.accepted, y.accepted);
      EXPECT_EQ(x.inliers, y.inliers);
      EXPECT_TRUE(x.measurement.matrix() == y.measurement.matrix());
      ++attempts;
    }
  }
  EXPECT_GT(attempts, 0u);
  // spilled: a holds its latest keyframe scan only (nothing else uses them now), the features none
  std::set<const void*> seen;
  const FrontendFootprint f = fa.footprint(seen);
  EXPECT_EQ(f.own_scans, fa.keyframes().size());
  EXPECT_LE(f.scan_bytes_in_memory, largest);
  EXPECT_GT(f.scan_bytes_spilled, (fa.keyframes().size() - 1) * largest / 2);
  const FrontendFootprint fbf = fb.footprint(seen);  // a's scans b received are a's KeptScans: counted already
  EXPECT_EQ(fbf.teammate_scans, 0u);
  EXPECT_LE(fbf.scan_bytes_in_memory, largest);  // b's latest
  EXPECT_EQ(fb.featureCache().footprint().bytes_in_memory, 0u);
  EXPECT_GT(fb.featureCache().footprint().bytes_spilled, 0u);
  // in memory: every keyframe scan is held
  std::set<const void*> seen_m;
  EXPECT_GT(ma.footprint(seen_m).scan_bytes_in_memory, (ma.keyframes().size() - 1) * largest / 2);
}

namespace {

std::string teamJrl(bool spill, unsigned registration_threads) {
  const auto& trials = team();
  std::vector<TrialSpan> spans;
  for (const auto& t : trials) spans.push_back({t.robot, t.scans.front().stamp, t.scans.back().stamp});
  const SequenceTiming timing = SequenceTiming::synchronize(spans, 'a', 0.5, 5);
  std::map<char, Trajectory> refs;
  for (const auto& t : trials) refs[t.robot] = toSensorReference(t.body, t.extrinsic, timing.of(t.robot));
  pipeline::TeamRunParams params;
  params.frontend = FrontendParams::loadDir(defaultConfigDir());
  params.frontend.spill_keyframes = spill;
  params.frontend.odometry = OdometryKind::Reference;
  params.registration_threads = registration_threads;
  pipeline::TeamRun run("test_team", refs, params, deriveSeed(5, "radio"), timing.start());
  std::map<char, std::unique_ptr<ScanSource>> sources;
  for (const auto& t : trials) sources[t.robot] = std::make_unique<VectorScanSource>(t.scans);
  MergedScanStream stream(std::move(sources), timing);
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) run.add(robot, OwnScan::of(scan));
  run.finish(timing.end());
  EXPECT_GT(run.counts().inter_accepted + run.counts().intra_accepted, 0u);
  const auto path = (std::filesystem::temp_directory_path() /
                     ("cosmo_kept_scan_" + std::to_string(spill) + std::to_string(registration_threads) + ".jrl"))
                        .string();
  run.recorder().write(path);
  std::string bytes = readWholeFileOrEmpty(path);
  std::filesystem::remove(path);
  return bytes;
}

}  // namespace

TEST(TeamRun, SpillingKeyframesGivesTheSameJrlBytes) {
  const std::string in_memory = teamJrl(false, 0);
  ASSERT_FALSE(in_memory.empty());
  EXPECT_EQ(in_memory, teamJrl(true, 0));
  EXPECT_EQ(in_memory, teamJrl(true, 2));
}
