// rostest gtest node for recorder_kill.test: SIGKILL the recorder twice during a lockstep run; the final JRL must be
// byte-identical to the uninterrupted run's (cosmo_generate's for the same settings).
#include <signal.h>
#include <std_msgs/Empty.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <mutex>
#include <numeric>

#include "cosmo/RecorderProgress.h"
#include "launch_support.hpp"

namespace {

struct Progress {
  std::mutex mutex;
  std::string session;
  std::uint64_t acked = 0;  ///< over all robots
  std::size_t sessions = 0;
};

}  // namespace

TEST(RecorderKill, TwoSigkillsLeaveTheJrlByteIdentical) {
  ros::NodeHandle nh;
  std::string jrl_path;
  ASSERT_TRUE(nh.getParam("/jrl_path", jrl_path));
  Progress progress;
  std::atomic<bool> done{false};
  auto progress_sub = nh.subscribe<cosmo::RecorderProgress>(
      "/recorder/progress", 10, [&](const cosmo::RecorderProgress::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(progress.mutex);
        if (m->session != progress.session) ++progress.sessions;
        progress.session = m->session;
        progress.acked = std::accumulate(m->acked.begin(), m->acked.end(), std::uint64_t{0});
      });
  auto done_sub = nh.subscribe<std_msgs::Empty>("/player/done", 1, [&](const std_msgs::Empty::ConstPtr&) { done = true; });
  const auto acked = [&] {
    std::lock_guard<std::mutex> lock(progress.mutex);
    return progress.acked;
  };
  const auto sessions = [&] {
    std::lock_guard<std::mutex> lock(progress.mutex);
    return progress.sessions;
  };

  // First kill: once the recorder acknowledged a few measurements.
  ASSERT_TRUE(cosmo::test::spinUntil([&] { return acked() >= 4; }, 300.0)) << "the recorder acknowledged nothing";
  int pid = cosmo::test::pidOf("/recorder");
  ASSERT_GT(pid, 0);
  const std::uint64_t first = acked();
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  std::cout << "SIGKILL 1 of the recorder (pid " << pid << ") at " << first << " measurements acknowledged"
            << std::endl;

  // Second kill: once its successor (resumed from the journal) acknowledged more.
  ASSERT_TRUE(cosmo::test::spinUntil([&] { return sessions() >= 2 && acked() >= first + 40; }, 120.0))
      << "the respawned recorder did not take over";
  pid = cosmo::test::pidOf("/recorder");
  ASSERT_GT(pid, 0);
  const std::uint64_t second = acked();
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  std::cout << "SIGKILL 2 of the recorder (pid " << pid << ") at " << second << " measurements acknowledged"
            << std::endl;

  ASSERT_TRUE(cosmo::test::spinUntil([&] { return done.load(); }, 400.0)) << "the player did not finish";
  EXPECT_GE(sessions(), 3u);
  ASSERT_TRUE(ros::service::waitForService("/recorder/write", ros::Duration(30.0)));
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("/recorder/write", trigger));
  ASSERT_TRUE(trigger.response.success) << trigger.response.message;
  std::cout << trigger.response.message << std::endl;
  const std::string metadata = cosmo::readWholeFileOrEmpty(jrl_path.substr(0, jrl_path.size() - 4) + ".recorder.yaml");
  EXPECT_NE(metadata.find("recorder_sessions: 3"), std::string::npos) << metadata;
  EXPECT_NE(metadata.find("complete: true"), std::string::npos) << metadata;

  const cosmo::test::OfflineRun offline = cosmo::test::OfflineRun::fromParams();
  const std::string offline_path = offline.run(std::filesystem::path(jrl_path).parent_path().string() + "_offline",
                                               std::filesystem::path(jrl_path).filename().string());
  ASSERT_FALSE(offline_path.empty());
  const std::string diff = cosmo::test::firstDifference(jrl_path, offline_path);
  EXPECT_TRUE(diff.empty()) << diff;
  if (diff.empty())
    std::cout << "after two SIGKILLs of the recorder, the JRL is byte-identical to the uninterrupted run's ("
              << cosmo::readWholeFileOrEmpty(jrl_path).size() << " bytes)" << std::endl;
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "recorder_kill_test");
  return RUN_ALL_TESTS();
}
