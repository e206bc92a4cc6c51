// rostest gtest node for frontend_kill.test: SIGKILL of a front-end in a lockstep run: the run stops within 30 s with
// a message naming it, the player's status says so (it exits 1), and the dataset so far is written marked
// incomplete, valid.
#include <signal.h>
#include <std_msgs/String.h>

#include <atomic>
#include <mutex>

#include "cosmo/RecorderProgress.h"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"
#include "launch_support.hpp"

TEST(FrontendKill, LockstepStopsWithinThirtySecondsAndTheDatasetIsMarkedIncomplete) {
  ros::NodeHandle nh;
  std::string jrl_path, status_file;
  ASSERT_TRUE(nh.getParam("/jrl_path", jrl_path));
  ASSERT_TRUE(nh.getParam("/status_file", status_file));
  std::mutex mutex;
  std::optional<cosmo::RecorderProgress> progress;
  std::optional<std::string> abort;
  auto progress_sub = nh.subscribe<cosmo::RecorderProgress>(
      "/recorder/progress", 10, [&](const cosmo::RecorderProgress::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        progress = *m;
      });
  auto abort_sub = nh.subscribe<std_msgs::String>("/player/abort", 1, [&](const std_msgs::String::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    abort = m->data;
  });
  const auto b_acked = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    const std::size_t i = progress ? progress->robots.find('b') : std::string::npos;
    return i == std::string::npos || i >= progress->acked.size() ? 0 : progress->acked[i];
  };
  ASSERT_TRUE(cosmo::test::spinUntil([&] { return b_acked() >= 3; }, 300.0)) << "robot b recorded nothing";
  const int pid = cosmo::test::pidOf("/b/frontend");
  ASSERT_GT(pid, 0);
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  const ros::WallTime killed = ros::WallTime::now();
  std::cout << "SIGKILL of /b/frontend (pid " << pid << ") with " << b_acked() << " of b's measurements recorded"
            << std::endl;

  const auto stopped = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return abort.has_value();
  };
  ASSERT_TRUE(cosmo::test::spinUntil(stopped, 30.0)) << "no /player/abort within 30 s of the kill";
  const double seconds = (ros::WallTime::now() - killed).toSec();
  std::cout << "the player stopped the run " << seconds << " s after the kill: " << *abort << std::endl;
  EXPECT_NE(abort->find("robot b (/b/frontend)"), std::string::npos) << *abort;

  // The recorder writes the dataset so far marked incomplete, and the player's status says it stopped.
  const auto written = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return progress && !progress->incomplete.empty();
  };
  ASSERT_TRUE(cosmo::test::spinUntil(written, 30.0)) << "the recorder did not report an incomplete write";
  std::cout << "recorder: " << progress->written << std::endl;
  ASSERT_TRUE(cosmo::test::spinUntil([&] { return !cosmo::readWholeFileOrEmpty(status_file).empty(); }, 40.0));
  EXPECT_EQ(cosmo::readWholeFileOrEmpty(status_file).rfind("stopped: ", 0), 0u) << cosmo::readWholeFileOrEmpty(status_file);
  const std::string metadata = cosmo::readWholeFileOrEmpty(jrl_path.substr(0, jrl_path.size() - 4) + ".recorder.yaml");
  EXPECT_NE(metadata.find("complete: false"), std::string::npos) << metadata;
  EXPECT_NE(metadata.find("incomplete: \"the player stopped the run: the front-end of robot b"), std::string::npos)
      << metadata;
  const cosmo::jrl::Dataset ds = cosmo::jrl::readJrl(jrl_path);
  for (const auto& v : cosmo::jrl::validate(ds)) ADD_FAILURE() << v.str();
  ASSERT_TRUE(ds.measurements.count('b'));
  EXPECT_GE(ds.measurements.at('b').size(), 2u) << "b's keyframes recorded before its death are in the dataset";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "frontend_kill_test");
  return RUN_ALL_TESTS();
}
