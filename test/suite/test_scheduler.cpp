// The scheduler's policy: widths from robots and cores, registration threads, the estimate first and its
// dependents after it, the longest work first, a failed estimate blocking its dependents; the progress line.
#include <gtest/gtest.h>

#include "cosmo/suite/plan_inputs.hpp"
#include "cosmo/suite/progress.hpp"
#include "cosmo/suite/scheduler.hpp"

using namespace cosmo::suite;

namespace {

Job job(const std::string& id, int robots, double seconds, std::vector<std::string> deps = {},
        Job::Kind kind = Job::Kind::Datasets) {
  Job j;
  j.id = id;
  j.robots = robots;
  j.seconds = seconds;
  j.depends_on = std::move(deps);
  j.kind = kind;
  return j;
}

}  // namespace

TEST(Scheduler, WidthsFillTheCoresWithoutOversubscribing) {
  EXPECT_EQ(jobWidth(3, {2, 0}), 2u);   // 3 robots + 1 registration thread, capped at 2 cores
  EXPECT_EQ(jobWidth(3, {16, 0}), 4u);  // 16 cores: four such jobs side by side
  EXPECT_EQ(jobWidth(5, {16, 0}), 6u);
  EXPECT_EQ(jobWidth(3, {2, 2}), 1u);   // --jobs 2 on 2 cores
  EXPECT_EQ(jobWidth(3, {16, 8}), 2u);
  EXPECT_EQ(registrationThreads(3, 4), 1u);
  EXPECT_EQ(registrationThreads(3, 6), 3u);
  EXPECT_EQ(registrationThreads(3, 2), 1u);  // at least one
}

TEST(Scheduler, EstimateFirstThenLongestWorkFirstAndOnlyWhatFits) {
  Plan plan;
  plan.jobs = {job("e", 1, 100, {}, Job::Kind::Estimate), job("short", 3, 100), job("cu", 4, 2000, {"e"}),
               job("long", 3, 600)};
  Scheduler s(plan, {"e", "short", "cu", "long"}, {8, 0});
  EXPECT_EQ(s.next(), 0);  // the estimate
  s.started(0);            // width 2 of 8
  EXPECT_EQ(s.next(), 3);  // "cu" waits for the estimate; "long" (1800 robot-s) before "short" (300)
  s.started(3);            // width 4: 2 cores left
  EXPECT_EQ(s.next(), -1);  // "short" needs 4
  s.finished(0, true);
  EXPECT_EQ(s.next(), -1);  // "cu" (8000 robot-s) may start now but needs 5 cores of the 4 free; "short" waits too
  s.finished(3, true);
  EXPECT_EQ(s.next(), 2);
  s.started(2);
  EXPECT_EQ(s.next(), -1);  // "short" needs 4 of the 3 free
  s.finished(2, true);
  EXPECT_EQ(s.next(), 1);
  s.started(1);
  s.finished(1, true);
  EXPECT_TRUE(s.allFinished());
}

TEST(Scheduler, OneJobAtATimeOnTwoCoresAndNAtATimeWithJobs) {
  Plan plan;
  plan.jobs = {job("a", 3, 10), job("b", 3, 10), job("c", 3, 10)};
  Scheduler one(plan, {"a", "b", "c"}, {2, 0});
  one.started(one.next());
  EXPECT_EQ(one.next(), -1);
  Scheduler two(plan, {"a", "b", "c"}, {2, 2});
  two.started(two.next());
  two.started(two.next());
  EXPECT_EQ(two.next(), -1);
  EXPECT_EQ(two.count(Scheduler::State::Running), 2u);
}

TEST(Scheduler, AFailedEstimateBlocksItsDependentsOnly) {
  Plan plan;
  plan.jobs = {job("e", 1, 10, {}, Job::Kind::Estimate), job("cu", 4, 10, {"e"}), job("ntu", 3, 10)};
  Scheduler s(plan, {"e", "cu", "ntu"}, {2, 0});
  s.started(s.next());
  s.finished(0, false);
  EXPECT_EQ(s.state(1), Scheduler::State::Blocked);
  EXPECT_EQ(s.blockedBy(1), "e");
  EXPECT_EQ(s.next(), 2);
  s.started(2);
  s.finished(2, true);
  EXPECT_TRUE(s.allFinished());
}

TEST(Scheduler, JobsNotToDoAreDone) {
  Plan plan;
  plan.jobs = {job("e", 1, 10, {}, Job::Kind::Estimate), job("cu", 4, 10, {"e"})};
  Scheduler s(plan, {"cu"}, {2, 0});  // the estimate is current
  EXPECT_EQ(s.next(), 1);
}

TEST(Progress, ReadsCosmoGeneratesProgressLinesPerCommModel) {
  const std::string log =
      "sequence x: 3 trials, 120.0 s\n"
      "[wifi]    0.0 / 120.0 s  keyframes 0\n[wifi]   60.5 / 120.0 s  keyframes 10\n"
      "[wifi]  120.0 / 120.0 s  keyframes 20\n[proradio]   30.0 / 120.0 s  keyframes 5\n";
  const LogProgress p = readLogProgress(log);
  EXPECT_DOUBLE_EQ(p.done_s, 150.0);
  EXPECT_DOUBLE_EQ(p.length_s, 120.0);
}

TEST(Progress, TheLineCountsDatasetsAndGivesAnEta) {
  ProgressCounts c;
  c.done = 2;
  c.skipped = 1;
  c.running = 2;
  c.left = 3;
  c.remaining_s = 600;
  c.processed_s = 300;
  c.elapsed_s = 100;
  EXPECT_EQ(progressLine(c),
            "[suite] 2 done, 1 skipped as current, 0 failed, 2 running, 3 left; 600 s of sequence to process, ETA "
            "3 min 20 s");
  c.processed_s = 0;
  EXPECT_EQ(progressLine(c).find("ETA"), std::string::npos);
  c.processed_s = 10;  // under 2 % of the 610 s: too early for a rate
  EXPECT_EQ(progressLine(c).find("ETA"), std::string::npos);
  EXPECT_EQ(formatDuration(3725), "1 h 02 min");
}

TEST(Scheduler, AFirstPassOverASharedBagRunsBeforeTheOthersThatReadItWhateverItsEnd) {
  Plan plan;
  plan.jobs = {job("ntu_r3_00", 3, 600), job("ntu_r5_00", 5, 685), job("kth", 3, 900)};
  orderFirstPasses(plan, {{"ntu_r3_00", {"/d/ntu_night_04.bag", "/d/ntu_day_01.bag"}},
                          {"ntu_r5_00", {"/d/ntu_night_04.bag", "/d/ntu_day_02.bag"}},
                          {"kth", {"/d/kth_day_06.bag"}}});
  EXPECT_EQ(plan.jobs[1].after, std::vector<std::string>{"ntu_r3_00"});
  EXPECT_TRUE(plan.jobs[0].after.empty());
  EXPECT_TRUE(plan.jobs[2].after.empty());
  Scheduler s(plan, {"ntu_r3_00", "ntu_r5_00", "kth"}, {16, 0});
  EXPECT_EQ(s.next(), 2);  // kth (2700 robot-s) first; ntu_r5_00 (3425) waits for ntu_r3_00's first pass
  s.started(2);
  EXPECT_EQ(s.next(), 0);
  s.started(0);
  EXPECT_EQ(s.next(), -1);
  s.finished(0, false);  // a failed first pass does not block it: it decompresses the bag itself
  EXPECT_EQ(s.next(), 1);
}
