// The end of a real-time run (pipeline/team_drain.hpp): a front-end is drained when it reports fresh, idle and
// unchanged for the quiet time, and the recorder holds what it sent.
#include <gtest/gtest.h>

#include "cosmo/pipeline/team_drain.hpp"

using namespace cosmo::pipeline;

namespace {
FrontendProgress at(std::uint32_t scans, std::uint64_t seq) {
  FrontendProgress p;
  p.scans = scans;
  p.seq = seq;
  return p;
}
}  // namespace

TEST(TeamDrain, DrainedWhenIdleUnchangedFreshAndRecorded) {
  TeamDrain d(2.0, 1.5);
  EXPECT_FALSE(d.drained('a', 100, 0.0)) << "never reported";
  d.reported('a', at(10, 5), 0, 0.0);
  EXPECT_FALSE(d.drained('a', 5, 1.0)) << "not quiet for 2 s yet";
  d.reported('a', at(10, 5), 0, 1.0);
  d.reported('a', at(10, 5), 0, 2.0);
  EXPECT_TRUE(d.drained('a', 5, 2.1));
  EXPECT_FALSE(d.drained('a', 4, 2.1)) << "the recorder does not hold measurement 5 yet";
  EXPECT_FALSE(d.drained('a', 5, 3.6)) << "no fresh report: busy";
  EXPECT_EQ(d.lastSeq('a'), 5u);
}

TEST(TeamDrain, WaitingScansOrMovingCountersAreNotDrained) {
  TeamDrain d(2.0, 1.5);
  d.reported('a', at(10, 5), 3, 0.0);
  d.reported('a', at(10, 5), 0, 1.0);
  EXPECT_FALSE(d.drained('a', 5, 2.5)) << "scans were waiting 2 s ago";
  d.reported('a', at(10, 5), 0, 2.9);
  EXPECT_TRUE(d.drained('a', 5, 3.0));
  d.reported('a', at(10, 6), 0, 3.5);  // a late delivery gave a loop closure
  EXPECT_FALSE(d.drained('a', 6, 4.0));
  d.reported('a', at(10, 6), 0, 5.4);
  EXPECT_TRUE(d.drained('a', 6, 5.5));
}
