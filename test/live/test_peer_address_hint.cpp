// The likely cause named for a peer that cannot be reached, per symptom.
#include <gtest/gtest.h>

#include "cosmo/live/peer_address_hint.hpp"

using namespace cosmo::live;

namespace {

bool says(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(PeerAddressHint, NamesTheCauseOfAnUnreachablePeer) {
  PeerAddress p{"http://robot-a:41234/", "robot-a"};
  p.resolved = false;
  EXPECT_TRUE(says(unreachableHint(p), "'robot-a' does not resolve")) << unreachableHint(p);
  EXPECT_TRUE(says(unreachableHint(p), "ROS_IP"));
  p = {"http://127.0.0.1:41234/", "127.0.0.1"};
  p.loopback = true;
  EXPECT_TRUE(says(unreachableHint(p), "loopback address 127.0.0.1")) << unreachableHint(p);
  p = {"http://10.1.2.3:41234/", "10.1.2.3"};
  p.timed_out = true;
  EXPECT_TRUE(says(unreachableHint(p), "nothing answers at 10.1.2.3")) << unreachableHint(p);
  p.timed_out = false;
  p.refused = true;
  EXPECT_TRUE(says(unreachableHint(p), "nothing listens at http://10.1.2.3:41234/")) << unreachableHint(p);
}

TEST(PeerAddressHint, NamesTheLoopbackAliasWhenOnlyTheTopicServerRefuses) {
  PeerAddress t{"127.0.0.2:38211", "127.0.0.2"};
  t.loopback = true;
  t.refused = true;
  EXPECT_TRUE(says(unlinkedHint(t), "ROS_HOSTNAME=127.0.0.2")) << unlinkedHint(t);
  t = {"10.0.0.5:38211", "10.0.0.5"};
  t.timed_out = true;
  EXPECT_TRUE(says(unlinkedHint(t), "firewall")) << unlinkedHint(t);
  EXPECT_TRUE(says(neverRegisteredHint("http://10.0.0.1:11311"), "ROS_MASTER_URI=http://10.0.0.1:11311"));
}
