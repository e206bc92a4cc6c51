// A live robot's clock out of step with the base's, told from its messages' stamps and arrival times.
#include <gtest/gtest.h>

#include "cosmo/live/clock_skew.hpp"

using namespace cosmo;
using namespace cosmo::live;

TEST(ClockSkewWatch, InStepClocksWithLatencyAndJitterSayNothing) {
  ClockSkewWatch w(0.2, 5.0, 5);
  for (int i = 0; i < 50; ++i) {
    const StampNs stamp = toStampNs(1000.0 + i);
    EXPECT_FALSE(w.observe('a', stamp, stamp + toStampNs(0.05 + 0.3 * (i % 3))));
  }
}

TEST(ClockSkewWatch, NamesARobotWhoseClockRunsAheadOnceUntilItIsBackInStep) {
  ClockSkewWatch w(0.2, 5.0, 3);
  std::optional<std::string> said;
  int warnings = 0;
  for (int i = 0; i < 10; ++i) {
    const StampNs arrival = toStampNs(1000.0 + i);
    if (auto m = w.observe('b', arrival + toStampNs(1.5), arrival)) said = m, ++warnings;  // stamped 1.5 s ahead
  }
  ASSERT_TRUE(said);
  EXPECT_EQ(warnings, 1);
  EXPECT_NE(said->find("robot b"), std::string::npos) << *said;
  EXPECT_NE(said->find("ahead"), std::string::npos) << *said;
  EXPECT_NE(said->find("chrony"), std::string::npos) << *said;
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(w.observe('b', toStampNs(2000.0 + i), toStampNs(2000.1 + i)));
  said.reset();
  for (int i = 0; i < 3; ++i)
    if (auto m = w.observe('b', toStampNs(3000.0 + i), toStampNs(2998.0 + i))) said = m;
  EXPECT_TRUE(said) << "warned again after it was in step in between";
}

TEST(ClockSkewWatch, NamesARobotWhoseMessagesAreAllLate) {
  ClockSkewWatch w(0.2, 5.0, 4);
  std::optional<std::string> said;
  for (int i = 0; i < 4; ++i) said = w.observe('c', toStampNs(1000.0 + i), toStampNs(1008.0 + i));
  ASSERT_TRUE(said);
  EXPECT_NE(said->find("behind"), std::string::npos) << *said;
  EXPECT_FALSE(w.observe('a', toStampNs(1000.0), toStampNs(1008.0))) << "another robot: its own window";
}
