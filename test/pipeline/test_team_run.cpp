// The offline driver's core: merged scan stream in sequence time, and TeamRun determinism (the same input and
// seed give a byte-identical JRL) on a short synthetic two-robot sequence.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>

#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/seed_streams.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/frontend/odometry_run_ahead.hpp"
#include "../support/synthetic_team.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;
using namespace cosmo::sequence;

namespace {

const std::vector<test::SyntheticTrial>& team() { return test::sharedSyntheticTeam(2, 50); }

SequenceTiming timingOf(const std::vector<test::SyntheticTrial>& trials, std::uint64_t seed, double sigma) {
  std::vector<TrialSpan> spans;
  for (const auto& t : trials) spans.push_back({t.robot, t.scans.front().stamp, t.scans.back().stamp});
  return SequenceTiming::synchronize(spans, 'a', sigma, seed);
}

std::map<char, std::unique_ptr<ScanSource>> sourcesOf(const std::vector<test::SyntheticTrial>& trials);

/// The trials' reference trajectories (sensor frame), each on the sequence clock.
std::map<char, Trajectory> referencesOf(const std::vector<test::SyntheticTrial>& trials, const SequenceTiming& timing) {
  std::map<char, Trajectory> refs;
  for (const auto& t : trials) refs[t.robot] = toSensorReference(t.body, t.extrinsic, timing.of(t.robot));
  return refs;
}

MergedScanStream streamOf(const std::vector<test::SyntheticTrial>& trials, const SequenceTiming& timing) {
  return MergedScanStream(sourcesOf(trials), timing);
}

/// One offline run; returns the JRL bytes.
std::string runOnce(std::uint64_t seed, TeamCounts* counts = nullptr, unsigned registration_threads = 0) {
  const auto& trials = team();
  // sigma 0.5 s: the short trials overlap in time, so the robots meet at the shared start
  const SequenceTiming timing = timingOf(trials, seed, 0.5);
  const std::map<char, Trajectory> refs = referencesOf(trials, timing);
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(defaultConfigDir());
  params.frontend.odometry = frontend::OdometryKind::Reference;
  params.registration_threads = registration_threads;
  TeamRun run("test_team", refs, params, cosmo::sequence::deriveSeed(seed, "radio"), timing.start());
  MergedScanStream stream = streamOf(trials, timing);
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) run.add(robot, frontend::OwnScan::of(scan));
  run.finish(timing.end());
  const auto path = (std::filesystem::temp_directory_path() /
                     ("cosmo_team_run_" + std::to_string(seed) + "_" + std::to_string(registration_threads) + ".jrl"))
                        .string();
  run.recorder().write(path);
  if (counts) *counts = run.counts();
  std::string bytes = cosmo::readWholeFileOrEmpty(path);
  std::filesystem::remove(path);
  return bytes;
}

std::map<char, std::unique_ptr<ScanSource>> sourcesOf(const std::vector<test::SyntheticTrial>& trials) {
  std::map<char, std::unique_ptr<ScanSource>> sources;
  for (const auto& t : trials) sources[t.robot] = std::make_unique<VectorScanSource>(t.scans);
  return sources;
}

/// A LOAM run of the first `max_scans` merged scans; `run_ahead`: odometry on worker threads that read their own
/// copies of the scans (OdometryRunAhead), as cosmo_generate does.
std::string runLoam(bool run_ahead, std::size_t max_scans, unsigned cores = 0, unsigned registration_threads = 0,
                    TeamCounts* counts = nullptr) {
  const auto& trials = team();
  const SequenceTiming timing = timingOf(trials, 3, 0.5);
  const std::map<char, Trajectory> refs = referencesOf(trials, timing);
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(defaultConfigDir());
  params.registration_threads = registration_threads;
  TeamRun run("test_team", refs, params, cosmo::sequence::deriveSeed(3, "radio"), timing.start());
  StampNs last = 0;
  if (run_ahead) {
    frontend::OdometryRunAhead ahead(sourcesOf(trials), timing, params.frontend, refs, cores);
    frontend::AheadScan s;
    for (std::size_t n = 0; n < max_scans && ahead.next(s); ++n) {
      run.add(s.robot, frontend::OwnScan::prepared(s.stamp, s.odometry, std::move(s.keyframe_scan)));
      last = s.stamp;
    }
  } else {
    MergedScanStream stream = streamOf(trials, timing);
    char robot;
    Scan scan;
    for (std::size_t n = 0; n < max_scans && stream.next(robot, scan); ++n) {
      run.add(robot, frontend::OwnScan::of(scan));
      last = scan.stamp;
    }
  }
  run.finish(last);
  const auto path = (std::filesystem::temp_directory_path() /
                     (std::string("cosmo_team_run_loam_") + (run_ahead ? "p" : "s") + std::to_string(cores) + "_" +
                      std::to_string(registration_threads) + ".jrl"))
                        .string();
  run.recorder().write(path);
  EXPECT_GT(run.counts().keyframes, 2u);
  if (counts) *counts = run.counts();
  std::string bytes = cosmo::readWholeFileOrEmpty(path);
  std::filesystem::remove(path);
  return bytes;
}

}  // namespace

TEST(TeamRun, OdometryOnWorkerThreadsGivesTheSameJrl) {
  const std::string serial = runLoam(false, 100), parallel = runLoam(true, 100);
  ASSERT_FALSE(serial.empty());
  EXPECT_EQ(serial, parallel);
  // One core: a worker runs only while the team's thread waits for it (admission), and nothing deadlocks.
  EXPECT_EQ(serial, runLoam(true, 100, 1));
}

TEST(OdometryRunAhead, HandsOverInTheTeamsStreamOrderWithItsDroppedScans) {
  std::vector<Scan> a(4), b(3);
  for (int i = 0; i < 4; ++i) a[i].stamp = 10000000000ULL + i * 100000000ULL;
  for (int i = 0; i < 3; ++i) b[i].stamp = 10000000000ULL + i * 150000000ULL;
  a[2].stamp = a[1].stamp;  // not increasing: the team's stream drops it, so must the worker
  const SequenceTiming timing = SequenceTiming::synchronize(
      {{'a', a.front().stamp, a.back().stamp}, {'b', b.front().stamp, b.back().stamp}}, 'a', 0.0, 1);
  std::map<char, std::unique_ptr<ScanSource>> team_sources, worker_sources;
  team_sources['a'] = std::make_unique<VectorScanSource>(a);
  team_sources['b'] = std::make_unique<VectorScanSource>(b);
  worker_sources['a'] = std::make_unique<VectorScanSource>(a);
  worker_sources['b'] = std::make_unique<VectorScanSource>(b);
  MergedScanStream stream(std::move(team_sources), timing);
  frontend::OdometryRunAhead ahead(std::move(worker_sources), timing, frontend::FrontendParams{}, {});
  char robot;
  Scan scan;
  frontend::AheadScan s;
  int n = 0;
  while (stream.next(robot, scan)) {
    ASSERT_TRUE(ahead.next(s));
    EXPECT_EQ(s.robot, robot);
    EXPECT_EQ(s.stamp, scan.stamp);
    EXPECT_FALSE(s.odometry.ok);                   // empty scans: motion-model fallback, never a throw
    EXPECT_EQ(s.keyframe_scan != nullptr, n < 2);  // each robot's first scan is its keyframe 0 (ties: 'a' first)
    ++n;
  }
  EXPECT_EQ(n, 6);
  EXPECT_FALSE(ahead.next(s));
  ahead.stop();
  EXPECT_EQ(ahead.dropped(), stream.dropped());
  EXPECT_EQ(ahead.dropped().at('a'), 1u);
}

TEST(TeamRun, PreparedKeyframesMustMatchTheFrontendsKeyframer) {
  TeamRunParams params;
  std::map<char, Trajectory> refs{{'a', Trajectory{}}};
  TeamRun run("t", refs, params, 1, 0);
  odometry::OdometryResult r;
  const auto kf = std::make_shared<const Scan>();
  EXPECT_THROW(run.add('a', frontend::OwnScan::prepared(1000, r, nullptr)),
               std::logic_error);  // keyframe 0 not prepared
  TeamRun run2("t", refs, params, 1, 0);
  run2.add('a', frontend::OwnScan::prepared(1000, r, kf));
  EXPECT_THROW(run2.add('a', frontend::OwnScan::prepared(2000, r, kf)), std::logic_error);  // no motion: not a keyframe
  EXPECT_THROW(run2.add('z', frontend::OwnScan::prepared(3000, r, nullptr)), std::invalid_argument);
}

TEST(MergedScanStream, MergesBySequenceTimeAndDropsNonIncreasingStamps) {
  std::vector<Scan> a(3), b(3);
  for (int i = 0; i < 3; ++i) {
    a[i].stamp = 10000000000ULL + i * 100000000ULL;
    b[i].stamp = 20000000000ULL + i * 100000000ULL;
  }
  b[2].stamp = b[1].stamp;  // not increasing: dropped
  const SequenceTiming timing = SequenceTiming::synchronize(
      {{'a', a.front().stamp, a.back().stamp}, {'b', b.front().stamp, b.back().stamp}}, 'a', 0.0, 1);
  std::map<char, std::unique_ptr<ScanSource>> sources;
  sources['a'] = std::make_unique<VectorScanSource>(a);
  sources['b'] = std::make_unique<VectorScanSource>(b);
  MergedScanStream stream(std::move(sources), timing);
  std::string order;
  std::vector<StampNs> stamps;
  char robot;
  Scan scan;
  while (stream.next(robot, scan)) {
    order += robot;
    stamps.push_back(scan.stamp);
  }
  EXPECT_EQ(order, "ababa");  // sigma 0: both start at t*, ties go to 'a'
  for (std::size_t i = 1; i < stamps.size(); ++i) EXPECT_LE(stamps[i - 1], stamps[i]);
  EXPECT_EQ(stream.dropped().at('b'), 1u);
}

TEST(TeamRun, SameInputAndSeedGiveAByteIdenticalJrl) {
  TeamCounts counts;
  const std::string first = runOnce(5, &counts);
  const std::string second = runOnce(5);
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, second);
  EXPECT_GT(counts.keyframes, 4u);
  EXPECT_EQ(counts.recorder_rejected, 0u);
  // The two robots start at the same junction within ~1 s: the radio delivers scans and the receiver finds
  // an inter-robot loop closure.
  EXPECT_GT(counts.transfers_delivered, 0u);
  EXPECT_GT(counts.inter_accepted, 0u);
}

TEST(TeamRun, RegistrationThreadsGiveTheSameJrlOnOneAndTwoCores) {
  TeamCounts serial_counts;
  const std::string serial = runLoam(false, 100, 0, 0, &serial_counts);
  ASSERT_FALSE(serial.empty());
  // the registrations ran: there is something to reorder
  ASSERT_GT(serial_counts.intra_accepted + serial_counts.intra_rejected + serial_counts.inter_accepted +
                serial_counts.inter_rejected,
            0u);
  for (unsigned cores : {1u, 2u}) {
    for (unsigned threads : {1u, 2u}) {
      SCOPED_TRACE("cores " + std::to_string(cores) + ", registration threads " + std::to_string(threads));
      TeamCounts counts;
      EXPECT_EQ(serial, runLoam(true, 100, cores, threads, &counts));
      // after finish() every registration is recorded and counted
      EXPECT_EQ(counts.intra_accepted, serial_counts.intra_accepted);
      EXPECT_EQ(counts.intra_rejected, serial_counts.intra_rejected);
      EXPECT_EQ(counts.inter_accepted, serial_counts.inter_accepted);
      EXPECT_EQ(counts.inter_rejected, serial_counts.inter_rejected);
    }
  }
  // registrations on threads with the scans fed on the team's thread (no run-ahead) too
  EXPECT_EQ(serial, runLoam(false, 100, 0, 2));
}

TEST(TeamRun, RegistrationThreadsKeepInterRobotClosuresAndTheirOrder) {
  TeamCounts inline_counts, threaded_counts;
  const std::string inline_jrl = runOnce(5, &inline_counts, 0);
  const std::string threaded = runOnce(5, &threaded_counts, 3);
  ASSERT_FALSE(inline_jrl.empty());
  EXPECT_EQ(inline_jrl, threaded);
  EXPECT_GT(threaded_counts.inter_accepted, 0u);
  EXPECT_EQ(threaded_counts.inter_accepted, inline_counts.inter_accepted);
  EXPECT_EQ(threaded_counts.transfers_delivered, inline_counts.transfers_delivered);
}

TEST(TeamRun, RegistrationThreadsStopCleanlyWithoutFinish) {
  // A run abandoned midway (an exception in the driver, Ctrl-C): destroying it with registrations still queued or
  // running must neither hang nor crash.
  const auto& trials = team();
  const SequenceTiming timing = timingOf(trials, 5, 0.5);
  const std::map<char, Trajectory> refs = referencesOf(trials, timing);
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(defaultConfigDir());
  params.frontend.odometry = frontend::OdometryKind::Reference;
  params.registration_threads = 2;
  std::size_t keyframes = 0;
  {
    TeamRun run("test_team", refs, params, cosmo::sequence::deriveSeed(5, "radio"), timing.start());
    ASSERT_NE(run.registrationPool(), nullptr);
    MergedScanStream stream = streamOf(trials, timing);
    char robot;
    Scan scan;
    for (int n = 0; n < 60 && stream.next(robot, scan); ++n) run.add(robot, frontend::OwnScan::of(scan));
    keyframes = run.counts().keyframes;
  }
  EXPECT_GT(keyframes, 2u);
}

TEST(TeamRun, ReplaysARadioTraceInsteadOfTheDistanceModel) {
  // A trace that keeps a and b disconnected for the whole run: nothing is delivered, where phi(d) delivers, and every
  // connectivity sample came from the trace.
  const auto& trials = team();
  const SequenceTiming timing = timingOf(trials, 5, 0.5);
  const auto deliveredWith = [&](const comm::RadioParams& radio, comm::RadioStats* stats) {
    TeamRunParams params;
    params.frontend = frontend::FrontendParams::loadDir(defaultConfigDir());
    params.frontend.odometry = frontend::OdometryKind::Reference;
    params.radio = radio;
    TeamRun run("test_team", referencesOf(trials, timing), params, deriveSeed(5, "radio"), timing.start());
    MergedScanStream stream = streamOf(trials, timing);
    char robot;
    Scan scan;
    while (stream.next(robot, scan)) run.add(robot, frontend::OwnScan::of(scan));
    run.finish(timing.end());
    *stats = run.radio().stats();
    return run.counts().transfers_delivered;
  };
  comm::RadioStats model, traced;
  EXPECT_GT(deliveredWith(comm::RadioParams::wifi(), &model), 0u);
  comm::RadioParams blackout = comm::RadioParams::wifi();
  std::istringstream text("robot_a,robot_b,start,duration,throughput_Bps,latency,connected\na,b,-10,100000,0,0,0\n");
  blackout.trace = std::make_shared<const comm::RadioTrace>(comm::RadioTrace::parse(text, "blackout.csv"));
  EXPECT_EQ(deliveredWith(blackout, &traced), 0u);
  EXPECT_GT(traced.trace_samples, 0u);
  EXPECT_EQ(traced.fallback_samples, 0u);
}
