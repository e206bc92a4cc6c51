// The peer policy (live/peer_watch.hpp): states from probes, and what the run does when a peer never
// connects, dies or restarts, per role and mode, with the times the driver passes in.
#include <gtest/gtest.h>

#include "cosmo/live/peer_watch.hpp"

using namespace cosmo::live;

namespace {

PeerProbe alive(int pid, const std::string& uri = "http://localhost:4000/") {
  PeerProbe p;
  p.registered = true;
  p.uri = uri;
  p.answered = true;
  p.pid = pid;
  return p;
}

PeerProbe dead(const std::string& uri = "http://localhost:4000/") {
  PeerProbe p;
  p.registered = true;
  p.uri = uri;
  p.refused = true;
  p.error = "connection refused";
  return p;
}

PeerProbe absent() { return PeerProbe{}; }

PeerWatch team(RunMode mode) {
  PeerWatch w(mode);
  w.expect("/a/frontend", PeerRole::Frontend, "the front-end of robot a");
  w.expect("/b/frontend", PeerRole::Frontend, "the front-end of robot b");
  w.expect("/comm_broker", PeerRole::Broker, "the comm_broker");
  w.expect("/recorder", PeerRole::Recorder, "the recorder");
  return w;
}

void allAlive(PeerWatch& w, double t) {
  w.observe("/a/frontend", alive(10, "http://h:1/"), t);
  w.observe("/b/frontend", alive(11, "http://h:2/"), t);
  w.observe("/comm_broker", alive(12, "http://h:3/"), t);
  w.observe("/recorder", alive(13, "http://h:4/"), t);
}

bool mentions(const std::vector<PeerNotice>& notices, const std::string& text) {
  for (const auto& n : notices)
    if (n.text.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(PeerWatch, StatesFollowTheProbes) {
  PeerWatch w = team(RunMode::Realtime);
  EXPECT_EQ(w.state("/a/frontend"), PeerState::Waiting);
  PeerProbe registered = dead();
  w.observe("/a/frontend", registered, 0.0);
  EXPECT_EQ(w.state("/a/frontend"), PeerState::Unreachable);
  w.observe("/a/frontend", alive(10), 1.0);
  EXPECT_EQ(w.state("/a/frontend"), PeerState::Alive);
  EXPECT_TRUE(w.alive("/a/frontend"));
  w.observe("/a/frontend", dead(), 2.0);
  EXPECT_EQ(w.state("/a/frontend"), PeerState::Gone);
  w.observe("/a/frontend", absent(), 3.0);
  EXPECT_EQ(w.state("/a/frontend"), PeerState::Gone);
  EXPECT_NE(w.describe("/a/frontend").find("no longer registered"), std::string::npos);
  w.observe("/a/frontend", alive(20, "http://localhost:4001/"), 4.0);
  EXPECT_EQ(w.state("/a/frontend"), PeerState::Restarted);
  EXPECT_TRUE(w.alive("/a/frontend"));
  // the same life answering again after a silence is not a restart
  w.observe("/b/frontend", alive(11), 0.0);
  w.observe("/b/frontend", dead(), 1.0);
  w.observe("/b/frontend", alive(11), 2.0);
  EXPECT_EQ(w.state("/b/frontend"), PeerState::Alive);
  EXPECT_THROW(w.state("/nobody"), std::invalid_argument);
}

TEST(PeerWatch, NothingIsJudgedBeforeStartAndConnectTimeoutsCountFromIt) {
  PeerWatch w = team(RunMode::Lockstep);
  EXPECT_TRUE(w.review(1000.0).empty());
  w.start(1000.0);
  EXPECT_FALSE(w.connected());
  EXPECT_TRUE(w.review(1004.0).empty()) << "named only after the notice period";
  const auto first = w.review(1005.0);
  EXPECT_TRUE(mentions(first, "waiting for the front-end of robot a (/a/frontend): not registered"));
  EXPECT_TRUE(w.review(1007.0).empty()) << "named again only after the notice period";
  EXPECT_FALSE(w.review(1010.1).empty());
  allAlive(w, 1011.0);
  EXPECT_TRUE(w.connected());
  EXPECT_TRUE(w.review(1040.0).empty());
  EXPECT_FALSE(w.stopReason());
}

TEST(PeerWatch, LockstepStopsWhenAFrontendNeverConnects) {
  PeerWatch w = team(RunMode::Lockstep);
  w.start(0.0);
  w.observe("/a/frontend", alive(10), 1.0);
  w.observe("/comm_broker", alive(12), 1.0);
  w.observe("/b/frontend", dead("http://10.0.0.7:4100/"), 1.0);
  w.review(29.0);
  EXPECT_FALSE(w.stopReason());
  w.review(30.0);
  ASSERT_TRUE(w.stopReason());
  EXPECT_NE(w.stopReason()->find("the front-end of robot b (/b/frontend) did not connect within 30 s"),
            std::string::npos);
  EXPECT_NE(w.stopReason()->find("registered at http://10.0.0.7:4100/"), std::string::npos);
  EXPECT_NE(w.stopReason()->find("ROS_IP"), std::string::npos) << "names the likely cause across hosts";
}

TEST(PeerWatch, RealtimeGoesOnWithoutAFrontendThatNeverConnects) {
  PeerWatch w = team(RunMode::Realtime);
  w.start(0.0);
  w.observe("/a/frontend", alive(10), 1.0);
  w.observe("/comm_broker", alive(12), 1.0);
  w.observe("/recorder", alive(13), 1.0);
  EXPECT_FALSE(w.connected());
  const auto notices = w.review(31.0);
  EXPECT_FALSE(w.stopReason());
  EXPECT_TRUE(w.connected());
  ASSERT_TRUE(mentions(notices, "going on without it: the front-end of robot b"));
  EXPECT_TRUE(notices.front().warning);
  EXPECT_TRUE(w.review(100.0).empty()) << "said once";
}

TEST(PeerWatch, AlivePeerWhoseTopicsDoNotConnectIsNotConnected) {
  PeerWatch w = team(RunMode::Lockstep);
  w.setLinked("/b/frontend", false);
  w.start(0.0);
  allAlive(w, 1.0);
  EXPECT_FALSE(w.connected());
  EXPECT_NE(w.describe("/b/frontend").find("topics are not connected"), std::string::npos);
  w.setLinked("/b/frontend", true);
  EXPECT_TRUE(w.connected());
}

TEST(PeerWatch, LockstepStopsWithinTheDeathGraceWhenAFrontendDies) {
  PeerWatch w = team(RunMode::Lockstep);
  w.start(0.0);
  allAlive(w, 1.0);
  w.review(2.0);
  w.observe("/b/frontend", dead("http://h:2/"), 100.0);
  const auto warned = w.review(100.0);
  EXPECT_TRUE(mentions(warned, "does not answer"));
  EXPECT_FALSE(w.stopReason());
  w.observe("/b/frontend", dead("http://h:2/"), 104.0);
  w.review(104.9);
  EXPECT_FALSE(w.stopReason());
  w.review(105.0);
  ASSERT_TRUE(w.stopReason());
  EXPECT_NE(w.stopReason()->find("the front-end of robot b (/b/frontend) died: pid 11"), std::string::npos);
  EXPECT_NE(w.stopReason()->find("the process has ended"), std::string::npos);
  // sticky: the first reason stays
  w.observe("/comm_broker", dead("http://h:3/"), 106.0);
  w.review(120.0);
  EXPECT_NE(w.stopReason()->find("robot b"), std::string::npos);
}

TEST(PeerWatch, ABriefSilenceIsNoDeath) {
  PeerWatch w = team(RunMode::Lockstep);
  w.start(0.0);
  allAlive(w, 1.0);
  w.observe("/a/frontend", dead("http://h:1/"), 10.0);
  w.review(10.0);
  w.observe("/a/frontend", alive(10, "http://h:1/"), 12.0);
  const auto back = w.review(12.0);
  EXPECT_TRUE(mentions(back, "answers again"));
  w.review(30.0);
  EXPECT_FALSE(w.stopReason());
}

TEST(PeerWatch, LockstepStopsWhenAFrontendRestarts) {
  PeerWatch w = team(RunMode::Lockstep);
  w.start(0.0);
  allAlive(w, 1.0);
  w.observe("/a/frontend", alive(99, "http://h:9/"), 2.0);
  w.review(2.0);
  ASSERT_TRUE(w.stopReason());
  EXPECT_NE(w.stopReason()->find("restarted (pid 10 -> 99)"), std::string::npos);
}

TEST(PeerWatch, RealtimeWaitsForARespawnedFrontendAndCarriesOn) {
  PeerWatch w = team(RunMode::Realtime);
  w.start(0.0);
  allAlive(w, 1.0);
  w.observe("/b/frontend", dead("http://h:2/"), 10.0);
  const auto gone = w.review(10.0);
  EXPECT_TRUE(mentions(gone, "waiting for the launch to respawn it"));
  w.observe("/b/frontend", alive(50, "http://h:7/"), 12.0);
  const auto back = w.review(12.0);
  EXPECT_TRUE(mentions(back, "the front-end of robot b (/b/frontend) restarted (pid 11 -> 50)"));
  EXPECT_TRUE(w.review(13.0).empty());
  EXPECT_FALSE(w.stopReason());
  // it may die again: announced again
  w.observe("/b/frontend", dead("http://h:7/"), 20.0);
  EXPECT_TRUE(mentions(w.review(20.0), "is gone"));
  w.observe("/b/frontend", alive(51, "http://h:8/"), 21.0);
  EXPECT_TRUE(mentions(w.review(21.0), "restarted (pid 50 -> 51)"));
  EXPECT_FALSE(w.stopReason());
}

TEST(PeerWatch, TheRecorderIsWaitedForUpToItsTimeoutInBothModes) {
  for (RunMode mode : {RunMode::Lockstep, RunMode::Realtime}) {
    PeerWatch w = team(mode);
    w.start(0.0);
    allAlive(w, 1.0);
    w.observe("/recorder", dead("http://h:4/"), 10.0);
    EXPECT_TRUE(mentions(w.review(10.0), "waiting for the launch to respawn it (up to 60 s)"));
    w.observe("/recorder", alive(70, "http://h:5/"), 20.0);
    EXPECT_TRUE(mentions(w.review(20.0), "resumes from its journal"));
    EXPECT_FALSE(w.stopReason()) << "a restarted recorder is no reason to stop";
    w.observe("/recorder", absent(), 30.0);
    w.review(89.0);
    EXPECT_FALSE(w.stopReason());
    w.review(90.0);
    ASSERT_TRUE(w.stopReason());
    EXPECT_NE(w.stopReason()->find("the recorder (/recorder) has been gone for 60 s"), std::string::npos);
  }
}

TEST(PeerWatch, ARecorderThatNeverStartsStopsTheRunAfterItsTimeout) {
  PeerWatch w = team(RunMode::Realtime);
  w.start(0.0);
  w.observe("/a/frontend", alive(10), 1.0);
  w.observe("/b/frontend", alive(11), 1.0);
  w.observe("/comm_broker", alive(12), 1.0);
  EXPECT_TRUE(w.connected()) << "the run may begin before the recorder answers";
  w.review(59.0);
  EXPECT_FALSE(w.stopReason());
  w.review(60.0);
  ASSERT_TRUE(w.stopReason());
  EXPECT_NE(w.stopReason()->find("the recorder (/recorder) did not connect within 60 s"), std::string::npos);
}

TEST(PeerWatch, BrokerPolicy) {
  PeerWatch lockstep = team(RunMode::Lockstep);
  lockstep.start(0.0);
  allAlive(lockstep, 1.0);
  lockstep.observe("/comm_broker", dead("http://h:3/"), 10.0);
  lockstep.review(15.0);
  ASSERT_TRUE(lockstep.stopReason());
  EXPECT_NE(lockstep.stopReason()->find("the comm_broker (/comm_broker) died"), std::string::npos);

  PeerWatch realtime = team(RunMode::Realtime);
  realtime.start(0.0);
  allAlive(realtime, 1.0);
  realtime.observe("/comm_broker", dead("http://h:3/"), 10.0);
  EXPECT_TRUE(mentions(realtime.review(100.0), "no scans are exchanged until it is back"));
  EXPECT_FALSE(realtime.stopReason());
}

TEST(PeerWatch, TheRecorderStopsWhenItsPlayerDies) {
  PeerWatch w(RunMode::Lockstep);
  w.expect("/player", PeerRole::Player, "the player");
  w.start(0.0);
  w.observe("/player", alive(5), 0.0);
  w.observe("/player", absent(), 3.0);
  w.review(7.9);
  EXPECT_FALSE(w.stopReason());
  w.review(8.0);
  ASSERT_TRUE(w.stopReason());
  EXPECT_NE(w.stopReason()->find("the player (/player) died"), std::string::npos);
}
