// Robot-side playback: the base's merge over the robots' announced stamps (AnnouncedStamps) and the scans the
// robots play on request (ScanReadAhead) give exactly the order and the scans of a merge over the trials
// themselves, drops included; and the team's timing and references made from the robots' announcements
// (TrialBasis) are the ones made from the files.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <random>

#include "cosmo/sequence/scan_read_ahead.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/sequence/trial_basis.hpp"

using namespace cosmo;
using namespace cosmo::sequence;

namespace {

/// Stamps increasing by about 0.1 s with, now and then, one that repeats or goes back (bad input the merge drops).
std::vector<Scan> trialScans(std::mt19937& rng, StampNs first, std::size_t n) {
  std::vector<Scan> scans;
  StampNs t = first;
  std::uniform_int_distribution<int> jitter(-3000000, 3000000), bad(0, 19);
  for (std::size_t i = 0; i < n; ++i) {
    Scan s;
    const int b = bad(rng);
    s.stamp = b == 0 ? t : b == 1 ? t - 50000000 : (t += 100000000 + jitter(rng));
    s.points = {Eigen::Vector3f(static_cast<float>(i), 0.0f, 0.0f)};  // which scan of the trial it is
    scans.push_back(s);
  }
  return scans;
}

SequenceTiming timingOf(const std::map<char, std::vector<Scan>>& trials) {
  std::vector<TrialSpan> spans;
  for (const auto& [r, scans] : trials) spans.push_back({r, scans.front().stamp, scans.back().stamp});
  return SequenceTiming::synchronize(spans, 'a', 5.0, 7);
}

/// One robot: its trial read through a ScanReadAhead, and the base's view of its announcements.
struct Robot {
  std::vector<Scan> trial;
  std::size_t read = 0;
  ScanReadAhead ahead{3};
  AnnouncedStamps announced;
  /// The robot reads until its window is full and announces it (what the trial player does after each request).
  void readAhead() {
    while (ahead.wantsMore()) {
      if (read == trial.size()) {
        ahead.endOfTrial();
        break;
      }
      ahead.add(trial[read++]);
      announced.announce(ahead.stamps(), ahead.ended());
    }
    announced.announce(ahead.stamps(), ahead.ended());
  }
};

/// The base's source of one robot: stamps only, read from the announcements (the robot reads on when asked).
class AnnouncedSource : public ScanSource {
 public:
  explicit AnnouncedSource(Robot& robot) : robot_(robot) {}
  bool next(Scan& scan) override {
    std::optional<StampNs> s = robot_.announced.take();
    if (!s && !robot_.announced.exhausted()) {
      robot_.readAhead();
      s = robot_.announced.take();
    }
    if (!s) return false;
    scan = Scan();
    scan.stamp = *s;
    return true;
  }

 private:
  Robot& robot_;
};

}  // namespace

TEST(ScanReadAhead, BaseMergeOverAnnouncedStampsPlaysTheSameScansInTheSameOrder) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::map<char, std::vector<Scan>> trials;
    std::uniform_int_distribution<int> count(1, 60);
    trials['a'] = trialScans(rng, 1000000000000, count(rng));
    trials['b'] = trialScans(rng, 1000200000000, count(rng));
    trials['c'] = trialScans(rng, 1000010000000, count(rng));
    const SequenceTiming timing = timingOf(trials);

    std::map<char, std::unique_ptr<ScanSource>> direct_sources;
    for (const auto& [r, scans] : trials) direct_sources[r] = std::make_unique<VectorScanSource>(scans);
    MergedScanStream direct(std::move(direct_sources), timing);

    std::map<char, Robot> robots;
    std::map<char, std::unique_ptr<ScanSource>> announced_sources;
    for (const auto& [r, scans] : trials) {
      robots[r].trial = scans;
      robots[r].readAhead();
      announced_sources[r] = std::make_unique<AnnouncedSource>(robots[r]);
    }
    MergedScanStream base(std::move(announced_sources), timing);

    char r1, r2;
    Scan s1, s2;
    std::size_t n = 0;
    while (direct.next(r1, s1)) {
      ASSERT_TRUE(base.next(r2, s2)) << "seed " << seed << ": the base's merge ended early at scan " << n;
      ASSERT_EQ(r1, r2) << "seed " << seed << " scan " << n;
      ASSERT_EQ(s1.stamp, s2.stamp) << "seed " << seed << " scan " << n;
      // the base asks robot r2 for its scan by its recorded stamp; the robot plays that very scan
      Robot& robot = robots[r2];
      const Scan played = robot.ahead.take(timing.of(r2).toRecorded(s2.stamp));
      ASSERT_EQ(played.points, s1.points) << "seed " << seed << " scan " << n;
      robot.readAhead();
      ++n;
    }
    EXPECT_FALSE(base.next(r2, s2)) << "seed " << seed;
    EXPECT_EQ(base.dropped().size(), 0u) << "the robots drop what does not increase before announcing";
    std::size_t dropped = 0;
    for (const auto& [r, robot] : robots) dropped += robot.ahead.dropped();
    std::size_t direct_dropped = 0;
    for (const auto& [r, d] : direct.dropped()) direct_dropped += d;
    EXPECT_EQ(dropped, direct_dropped) << "seed " << seed;
  }
}

TEST(ScanReadAhead, KeepsAtMostItsCapacityAndSaysWhatItHolds) {
  ScanReadAhead ahead(3);
  Scan s;
  for (StampNs t : {10, 20, 30}) {
    EXPECT_TRUE(ahead.wantsMore());
    s.stamp = t;
    EXPECT_TRUE(ahead.add(s));
  }
  EXPECT_FALSE(ahead.wantsMore());
  EXPECT_EQ(ahead.stamps(), (std::vector<StampNs>{10, 20, 30}));
  EXPECT_EQ(ahead.take(20).stamp, 20);  // 10 was passed over by the base
  EXPECT_EQ(ahead.skipped(), 1u);
  EXPECT_THROW(ahead.take(25), std::runtime_error);
  s.stamp = 30;
  EXPECT_FALSE(ahead.add(s));  // not increasing: dropped
  EXPECT_EQ(ahead.dropped(), 1u);
  ahead.endOfTrial();
  EXPECT_FALSE(ahead.wantsMore());
  EXPECT_TRUE(ahead.ended());
}

TEST(AnnouncedStamps, TakesEachStampOnceAndRejectsWindowsThatLoseScans) {
  AnnouncedStamps a;
  EXPECT_FALSE(a.heard());
  EXPECT_FALSE(a.take());
  a.announce({10, 20}, false);
  a.announce({10, 20, 30}, false);  // the same scans again, and one more
  EXPECT_EQ(a.take(), StampNs{10});
  EXPECT_EQ(a.take(), StampNs{20});
  a.announce({20, 30, 40}, false);  // 10 was played; 20 not yet
  EXPECT_EQ(a.take(), StampNs{30});
  EXPECT_THROW(a.announce({50}, false), std::runtime_error);  // 40 is announced and not taken yet
  EXPECT_THROW(a.announce({40, 40}, false), std::runtime_error);
  a.announce({40}, true);
  EXPECT_FALSE(a.exhausted());
  EXPECT_EQ(a.take(), StampNs{40});
  EXPECT_TRUE(a.exhausted());
  EXPECT_FALSE(a.take());
  EXPECT_EQ(a.taken(), 4u);
}

TEST(TrialBasis, TimingAndReferencesAreTheOnesMadeFromTheFiles) {
  SequenceConfig config;
  config.seed = 3;
  config.anchor = 'b';
  config.time_offset_sigma = 10.0;
  config.reference_offset.mode = ReferenceOffsetConfig::Mode::Anchor;
  config.trials.resize(2);
  config.trials[0].robot = 'a';
  config.trials[1].robot = 'b';
  config.trials[1].extrinsic.translation() = Eigen::Vector3d(0.1, 0.2, 0.3);
  std::map<char, TrialBasis> basis;
  Trajectory ref_a, ref_b;
  for (int i = 0; i < 10; ++i) {
    Pose3 p = Pose3::Identity();
    p.translation() = Eigen::Vector3d(1000.4 + i, 2000.6, 3.2);
    ref_a.append(5000000000 + i * 100000000LL, p);
    ref_b.append(9000000000 + i * 100000000LL, p);
  }
  basis['a'] = {{'a', 5000000000, 5900000000}, ref_a};
  basis['b'] = {{'b', 9100000000, 9800000000}, ref_b};
  const SequenceTiming timing = synchronizeTrials(config, basis);
  const SequenceTiming expected = SequenceTiming::synchronize(
      {{'a', 5000000000, 5900000000}, {'b', 9100000000, 9800000000}}, 'b', 10.0, 3);
  ASSERT_EQ(timing.trials().size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(timing.trials()[i].offset_ns, expected.trials()[i].offset_ns);
  const auto refs = sensorReferences(config, basis, timing);
  const Eigen::Vector3d offset = roundedFirstPosition(ref_b);
  EXPECT_EQ(offset, Eigen::Vector3d(1000, 2001, 3));
  const Trajectory b = toSensorReference(ref_b, config.trials[1].extrinsic, timing.of('b'), offset);
  ASSERT_EQ(refs.at('b').size(), b.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    EXPECT_EQ(refs.at('b').poses()[i].stamp, b.poses()[i].stamp);
    EXPECT_EQ(refs.at('b').poses()[i].pose.matrix(), b.poses()[i].pose.matrix());
  }
  basis.erase('a');
  EXPECT_THROW(synchronizeTrials(config, basis), std::runtime_error);
}

TEST(ScanReadAhead, ARestartedPlayerReadsForwardToWhereTheBaseIs) {
  ScanReadAhead ahead(2);
  Scan s;
  for (StampNs t : {10, 20}) {
    s.stamp = t;
    ahead.add(s);
  }
  EXPECT_FALSE(ahead.passOver(40));  // the base asks for a scan further on: read on, beyond the capacity
  for (StampNs t : {30, 40, 50}) {
    s.stamp = t;
    ahead.add(s);
    if (ahead.passOver(40)) break;
  }
  EXPECT_EQ(ahead.take(40).stamp, 40);
  EXPECT_EQ(ahead.skipped(), 3u);
  ahead.endOfTrial();
  EXPECT_THROW(ahead.take(60), std::runtime_error);
}
