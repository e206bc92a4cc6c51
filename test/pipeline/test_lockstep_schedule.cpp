// The team's event order (pipeline/lockstep_schedule.hpp) as the lockstep player drives the nodes through it:
// when a scan needs the radio stepped first, when it waits for the scans before it, and the conditions the
// player waits on (scans processed, deliveries processed, the recorder's intake complete).
#include <gtest/gtest.h>

#include "cosmo/pipeline/lockstep_schedule.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;

namespace {
FrontendProgress progress(StampNs last, std::uint32_t scans, std::uint32_t received = 0, std::uint32_t keyframes = 0,
                          std::uint32_t closures = 0) {
  FrontendProgress p;
  p.last_scan = last;
  p.scans = scans;
  p.received = received;
  p.keyframes = keyframes;
  p.loop_closures = closures;
  return p;
}
}  // namespace

TEST(LockstepSchedule, TheFirstScanStepsTheRadioThenScansBeforeTheNextStepGoInParallel) {
  LockstepSchedule s({'a', 'b'}, true);
  auto first = s.beforeScan('a', 1000);
  EXPECT_TRUE(first.step_radio);
  EXPECT_TRUE(first.wait_for_scans);
  s.radioStepped(1100, {});
  s.scanHandedOver('a', 1000);
  // b's scan before the next step: no wait for a's scan, no radio step
  auto b = s.beforeScan('b', 1050);
  EXPECT_FALSE(b.step_radio);
  EXPECT_FALSE(b.wait_for_scans);
  s.scanHandedOver('b', 1050);
  // a's next scan waits for a's previous one (and so for every scan handed over), still no radio step
  auto a2 = s.beforeScan('a', 1060);
  EXPECT_FALSE(a2.step_radio);
  EXPECT_TRUE(a2.wait_for_scans);
  EXPECT_FALSE(s.scansProcessed());
  EXPECT_EQ(s.robotsBehind(), (std::vector<char>{'a', 'b'}));
  s.frontendReported('a', progress(1000, 1));
  s.frontendReported('b', progress(1050, 1));
  EXPECT_TRUE(s.scansProcessed());
  // a scan at the next step's stamp steps the radio first
  EXPECT_TRUE(s.beforeScan('b', 1100).step_radio);
  EXPECT_TRUE(s.beforeScan('b', 1100).wait_for_scans);
}

TEST(LockstepSchedule, AnOlderReportDoesNotUndoANewerOne) {
  LockstepSchedule s({'a'}, true);
  s.scanHandedOver('a', 2000);
  s.frontendReported('a', progress(2000, 2));
  s.frontendReported('a', progress(1000, 2, 1));  // a delivery processed, reported with an older scan stamp
  EXPECT_TRUE(s.scansProcessed());
  EXPECT_EQ(s.progress('a').last_scan, 2000u);
  EXPECT_EQ(s.progress('a').received, 1u);
}

TEST(LockstepSchedule, AReportThatComesBeforeTheHandOverIsNotWaitedFor) {
  LockstepSchedule s({'a'}, true);
  s.frontendReported('a', progress(3000, 1));  // the front-end was faster than the driver's bookkeeping
  s.scanHandedOver('a', 3000);
  EXPECT_TRUE(s.scansProcessed());
  s.scanHandedOver('a', 3100);
  EXPECT_FALSE(s.scansProcessed());
}

TEST(LockstepSchedule, WithoutARadioOnlyARobotsOwnScansWait) {
  LockstepSchedule s({'a', 'b'}, false);
  EXPECT_FALSE(s.beforeScan('a', 1000).step_radio);
  EXPECT_FALSE(s.beforeScan('a', 1000).wait_for_scans);
  s.scanHandedOver('a', 1000);
  EXPECT_FALSE(s.beforeScan('b', 1000).wait_for_scans);
  EXPECT_TRUE(s.beforeScan('a', 1100).wait_for_scans);
  s.stopWaitingForScans();  // a silent front-end: the player goes on
  EXPECT_TRUE(s.scansProcessed());
}

TEST(LockstepSchedule, TheRadioOrderCarriesWhoIsOnAndTheOffersItMustHaveSeen) {
  LockstepSchedule s({'a', 'b', 'c'}, true);
  s.frontendReported('a', progress(1000, 3, 0, 2));
  s.frontendReported('c', progress(1000, 1, 0, 1));
  const RadioStepOrder o = s.radioStepOrder(5000);
  EXPECT_EQ(o.through, 5000u);
  EXPECT_EQ(o.robots, (std::vector<char>{'a', 'b', 'c'}));
  EXPECT_EQ(o.on, (std::vector<bool>{true, false, true}));
  EXPECT_EQ(o.keyframes, (std::vector<std::uint32_t>{2, 0, 1}));
}

TEST(LockstepSchedule, DeliveriesCountAsProcessedOnceTheReceiverReportsThem) {
  LockstepSchedule s({'a', 'b'}, true);
  s.radioStepped(2000, {{'a', 0}, {'b', 2}});
  EXPECT_FALSE(s.deliveriesProcessed());
  s.frontendReported('b', progress(1000, 1, 1));
  EXPECT_FALSE(s.deliveriesProcessed());
  s.frontendReported('b', progress(1000, 1, 2));
  EXPECT_TRUE(s.deliveriesProcessed());
}

TEST(LockstepSchedule, TheRecorderIsCompleteWhenItHoldsWhatTheFrontendsSent) {
  LockstepSchedule s({'a', 'b'}, true);
  FrontendProgress a = progress(1000, 5, 0, 3, 1);
  a.seq = 4;  // 3 keyframes and a loop closure
  s.frontendReported('a', a);
  EXPECT_TRUE(s.recorderComplete());  // no recorder has reported: nothing to wait for
  s.recorderReported('a', 3);
  EXPECT_FALSE(s.recorderComplete());
  EXPECT_EQ(s.robotsNotRecorded(), (std::vector<char>{'a'}));
  s.recorderReported('a', 4);
  EXPECT_TRUE(s.recorderComplete());
  FrontendProgress b = progress(1000, 2, 0, 1, 0);
  b.seq = 1;
  s.frontendReported('b', b);
  EXPECT_FALSE(s.recorderComplete());
  s.recorderReported('b', 1);
  EXPECT_TRUE(s.recorderComplete());
}

TEST(LockstepSchedule, AnExpectedRecorderIsWaitedForBeforeItReports) {
  LockstepSchedule s({'a'}, true);
  s.expectRecorder();
  FrontendProgress a = progress(1000, 5, 0, 1, 0);
  a.seq = 1;
  s.frontendReported('a', a);
  EXPECT_FALSE(s.recorderComplete());
  s.recorderReported('a', 1);
  EXPECT_TRUE(s.recorderComplete());
}
