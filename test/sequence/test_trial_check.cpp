// The pre-flight check's line and reasons for each thing a trial's bag can turn out to be: each its own words, the
// data-root hint's "NOT FOUND" only for a bag that is not there.
#include <gtest/gtest.h>

#include "cosmo/sequence/trial_check.hpp"

using namespace cosmo;
using namespace cosmo::sequence;

namespace {

TrialConfig trial() {
  TrialConfig t;
  t.name = "kth_day_06";
  t.robot = 'a';
  t.bag = "/data/kth_day_06.bag";
  t.topic = "/os_cloud_node/points";
  return t;
}

TrialCheck checkOf(BagState state, const std::string& error) {
  TrialProbe probe;
  probe.bag = state;
  probe.error = error;
  return checkTrial(trial(), probe, {}, "", "");
}

}  // namespace

TEST(TrialCheck, EachBagStateHasItsOwnWords) {
  const struct {
    BagState state;
    const char* words;
  } cases[] = {{BagState::Missing, "bag NOT FOUND /data/kth_day_06.bag"},
               {BagState::Unreadable, "bag UNREADABLE /data/kth_day_06.bag"},
               {BagState::NotABag, "NOT A BAG /data/kth_day_06.bag"},
               {BagState::Damaged, "bag DAMAGED /data/kth_day_06.bag"},
               {BagState::Empty, "bag EMPTY /data/kth_day_06.bag (a recording of no messages)"}};
  for (const auto& c : cases) {
    const TrialCheck check = checkOf(c.state, "the reader's reason");
    EXPECT_EQ(check.line, std::string("robot a  kth_day_06: ") + c.words);
    ASSERT_EQ(check.errors.size(), 1u);
    EXPECT_EQ(check.errors[0], "kth_day_06: the reader's reason");
    if (c.state != BagState::Missing) EXPECT_EQ(check.line.find("NOT FOUND"), std::string::npos) << check.line;
  }
}

TEST(TrialCheck, AnEmptyTopicIsNamedAsEmpty) {
  TrialProbe probe;
  probe.bag = BagState::Ok;
  probe.topic_found = true;
  probe.topics = {"/os_cloud_node/points (sensor_msgs/PointCloud2)"};
  const TrialCheck check = checkTrial(trial(), probe, {}, "", "");
  EXPECT_EQ(check.line, "robot a  kth_day_06: bag ok, topic /os_cloud_node/points (0 scans): EMPTY");
  ASSERT_EQ(check.errors.size(), 1u);
  EXPECT_NE(check.errors[0].find("holds no messages"), std::string::npos) << check.errors[0];
}
