// rostest gtest node for frontend_respawn.test: SIGKILL of a front-end in a real-time run: it is respawned, continues
// its robot, the run completes, nothing recorded before the death is lost and the restart is in the metadata.
#include <signal.h>
#include <std_msgs/Empty.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <mutex>

#include "cosmo/RecorderProgress.h"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"
#include "launch_support.hpp"

TEST(FrontendRespawn, RealtimeCarriesOnAndRecordsTheRestart) {
  ros::NodeHandle nh;
  std::string jrl_path, status_file;
  ASSERT_TRUE(nh.getParam("/jrl_path", jrl_path));
  ASSERT_TRUE(nh.getParam("/status_file", status_file));
  std::mutex mutex;
  std::optional<cosmo::RecorderProgress> progress;
  std::atomic<bool> done{false};
  auto progress_sub = nh.subscribe<cosmo::RecorderProgress>(
      "/recorder/progress", 10, [&](const cosmo::RecorderProgress::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        progress = *m;
      });
  auto done_sub = nh.subscribe<std_msgs::Empty>("/player/done", 1, [&](const std_msgs::Empty::ConstPtr&) { done = true; });
  const auto b_chain_end = [&]() -> int {
    std::lock_guard<std::mutex> lock(mutex);
    const std::size_t i = progress ? progress->robots.find('b') : std::string::npos;
    return i == std::string::npos || i >= progress->chain_end.size() ? -1 : progress->chain_end[i];
  };
  ASSERT_TRUE(cosmo::test::spinUntil([&] { return b_chain_end() >= 2; }, 300.0)) << "robot b recorded nothing";
  const int pid = cosmo::test::pidOf("/b/frontend");
  ASSERT_GT(pid, 0);
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  const int recorded = b_chain_end();
  std::cout << "SIGKILL of /b/frontend (pid " << pid << ") with b's keyframes 0.." << recorded << " recorded"
            << std::endl;
  ASSERT_TRUE(cosmo::test::spinUntil(
      [&] {
        const int again = cosmo::test::pidOf("/b/frontend");
        return again > 0 && again != pid;
      },
      30.0))
      << "the front-end of b was not respawned";
  ASSERT_TRUE(cosmo::test::spinUntil([&] { return done.load(); }, 300.0)) << "the player did not finish";
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(status_file), "done\n");

  ASSERT_TRUE(ros::service::waitForService("/recorder/write", ros::Duration(30.0)));
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("/recorder/write", trigger));
  ASSERT_TRUE(trigger.response.success) << trigger.response.message;
  std::cout << trigger.response.message << std::endl;
  const cosmo::jrl::Dataset ds = cosmo::jrl::readJrl(jrl_path);
  for (const auto& v : cosmo::jrl::validate(ds)) ADD_FAILURE() << v.str();
  ASSERT_TRUE(ds.initialization && ds.initialization->count('b'));
  for (int i = 0; i <= recorded; ++i)
    EXPECT_TRUE(ds.initialization->at('b').count(cosmo::jrl::symbol('b', static_cast<std::uint64_t>(i))))
        << "keyframe b" << i << ", recorded before the death, is missing";
  const std::string metadata = cosmo::readWholeFileOrEmpty(jrl_path.substr(0, jrl_path.size() - 4) + ".recorder.yaml");
  EXPECT_NE(metadata.find("frontend_restarts: {a: 0, b: 1, c: 0}"), std::string::npos) << metadata;
  EXPECT_NE(metadata.find("  - {robot: b, from: b"), std::string::npos) << metadata;
  EXPECT_NE(metadata.find("rule: reference}"), std::string::npos) << metadata;
  std::cout << metadata << std::endl;
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "frontend_respawn_test");
  return RUN_ALL_TESTS();
}
