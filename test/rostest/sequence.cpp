// rostest gtest node for sequence.test: waits for the player to finish, makes the recorder write, and checks
// the JRL: `cosmo_jrl validate` passes, every robot has a complete odometry chain, and the outlier labels
// follow the default (fidelity) chi^2 rule, recomputed here from the file's own ground truth and covariances.
// Then (issue 8, determinism) the offline driver cosmo_generate runs the same sequence (the player's resolved
// config and seed), comm model, odometry, noise models and length, and its JRL must be byte-identical to the
// lockstep launch's.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Empty.h>
#include <std_srvs/Trigger.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/validate.hpp"
#include "cosmo/common/whole_file.hpp"
#include "launch_support.hpp"

namespace {

using cosmo::test::siblingProgram;

std::string shellQuote(const std::string& s) { return "'" + s + "'"; }

}  // namespace

TEST(SequenceLaunch, WritesAValidJrl) {
  ros::NodeHandle nh;
  std::string jrl_path;
  ASSERT_TRUE(nh.getParam("/jrl_path", jrl_path));
  std::atomic<bool> done{false};
  auto sub = nh.subscribe<std_msgs::Empty>("/player/done", 1, [&](const std_msgs::Empty::ConstPtr&) { done = true; });
  const ros::WallTime start = ros::WallTime::now();
  while (ros::ok() && !done && (ros::WallTime::now() - start).toSec() < 540.0) {
    ros::spinOnce();
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_TRUE(done) << "the player did not finish";
  ASSERT_TRUE(ros::service::waitForService("/recorder/write", ros::Duration(30.0)));
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("/recorder/write", trigger));
  EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  ASSERT_TRUE(std::filesystem::exists(jrl_path)) << jrl_path;

  const std::string cmd = "'" + siblingProgram("cosmo_jrl") + "' validate '" + jrl_path + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;

  const cosmo::jrl::Dataset ds = cosmo::jrl::readJrl(jrl_path);
  const auto violations = cosmo::jrl::validate(ds);
  for (const auto& v : violations) ADD_FAILURE() << v.str();
  const auto stats = cosmo::jrl::computeStats(ds);
  std::cout << cosmo::jrl::formatStats(stats) << std::endl;
  EXPECT_EQ(stats.robots.size(), 3u);
  EXPECT_EQ(stats.priors, 3u);
  EXPECT_GT(stats.odometry, 10u);
  EXPECT_TRUE(stats.has_groundtruth);
  EXPECT_TRUE(stats.has_outlier_labels);
  EXPECT_LE(stats.lc_outliers, stats.lc_count);
  EXPECT_LE(stats.irlc_outliers, stats.irlc_count);
  // the robots start at the same junction: scans exchanged there give inter-robot loop closures
  EXPECT_GT(stats.irlc_count, 0u);
  // robot a drives around a block back to its start: its return gives intra-robot loop closures
  EXPECT_GT(stats.lc_count, 0u);

  // Outlier labels: a loop closure is listed as an outlier iff it fails the default (fidelity) chi^2 rule
  // against the file's own ground truth and covariance.
  ASSERT_TRUE(ds.groundtruth && ds.outliers && ds.potential_outliers);
  auto listed = [](const std::map<char, std::set<cosmo::jrl::FactorId>>& m, char r, const cosmo::jrl::FactorId& id) {
    auto it = m.find(r);
    return it != m.end() && it->second.count(id) > 0;
  };
  std::size_t checked = 0;
  for (char r : ds.robots) {
    const auto& entries = ds.measurements.at(r);
    for (std::size_t e = 0; e < entries.size(); ++e)
      for (std::size_t f = 0; f < entries[e].factors.size(); ++f) {
        const auto& factor = entries[e].factors[f];
        const cosmo::jrl::FactorId id{e, f};
        if (!factor.isBetweenPose3() || !listed(*ds.potential_outliers, r, id)) continue;
        const auto& gt = ds.groundtruth->at(r);
        const cosmo::Pose3 truth =
            cosmo::jrl::pose3At(gt, factor.keys[0]).inverse() * cosmo::jrl::pose3At(gt, factor.keys[1]);
        const cosmo::Matrix6 cov = factor.covarianceMatrix();
        const bool outlier =
            cosmo::dataset::isOutlier(factor.pose3(), truth, cov, cosmo::dataset::OutlierRule::Fidelity);
        EXPECT_EQ(outlier, listed(*ds.outliers, r, id)) << r << " entry " << e << " factor " << f;
        ++checked;
      }
  }
  std::cout << "checked the labels of " << checked << " loop closures" << std::endl;
}

// Runs after WritesAValidJrl (which waited for the player and made the recorder write).
TEST(SequenceLaunch, LockstepJrlIsByteIdenticalToTheOfflineDriver) {
  ros::NodeHandle nh;
  std::string jrl_path, mode, sequence, seed, comm, odometry, noise_models, config_dir;
  double max_seconds = 0.0;
  ASSERT_TRUE(nh.getParam("/jrl_path", jrl_path));
  nh.param<std::string>("/mode", mode, "lockstep");
  if (mode != "lockstep") GTEST_SKIP() << "mode " << mode << ": only lockstep is deterministic";
  ASSERT_TRUE(nh.getParam("/player/resolved_sequence", sequence)) << "the player did not resolve its sequence";
  ASSERT_TRUE(nh.getParam("/player/resolved_seed", seed));
  ASSERT_TRUE(nh.getParam("/comm", comm));
  ASSERT_TRUE(nh.getParam("/odometry", odometry));
  ASSERT_TRUE(nh.getParam("/noise_models", noise_models));
  ASSERT_TRUE(nh.getParam("/config_dir", config_dir));
  nh.param("/max_seconds", max_seconds, 0.0);
  ASSERT_TRUE(std::filesystem::exists(jrl_path)) << jrl_path;

  const std::string out_dir = std::filesystem::path(jrl_path).parent_path().string() + "_offline";
  std::filesystem::remove_all(out_dir);
  std::ostringstream cmd;
  cmd << shellQuote(siblingProgram("cosmo_generate")) << " " << shellQuote(sequence) << " --seed " << seed << " --comm "
      << comm << " --config-dir " << shellQuote(config_dir) << " --noise-models " << shellQuote(noise_models)
      << " --out " << shellQuote(out_dir) << " --quiet" << (odometry == "reference" ? " --odometry reference" : "");
  if (max_seconds > 0) cmd << " --max-seconds " << max_seconds;
  cmd << " > " << shellQuote(out_dir + ".log") << " 2>&1";
  const ros::WallTime start = ros::WallTime::now();
  ASSERT_EQ(std::system(cmd.str().c_str()), 0) << cmd.str();
  std::cout << "cosmo_generate: " << (ros::WallTime::now() - start).toSec() << " s wall" << std::endl;

  const std::string offline_path = out_dir + "/" + std::filesystem::path(jrl_path).filename().string();
  ASSERT_TRUE(std::filesystem::exists(offline_path)) << offline_path << " (" << cmd.str() << ")";
  const std::string ros_bytes = cosmo::readWholeFileOrEmpty(jrl_path),
                    offline_bytes = cosmo::readWholeFileOrEmpty(offline_path);
  if (ros_bytes == offline_bytes) {
    std::cout << "lockstep launch and cosmo_generate wrote the same " << ros_bytes.size() << " bytes" << std::endl;
    return;
  }
  // the first difference: its line, and the text around it (a JRL may be one long line)
  std::size_t at = 0;
  while (at < ros_bytes.size() && at < offline_bytes.size() && ros_bytes[at] == offline_bytes[at]) ++at;
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(ros_bytes.begin(), ros_bytes.begin() + at, '\n'));
  const std::size_t from = at > 200 ? at - 200 : 0;
  ADD_FAILURE() << "JRL differs: " << jrl_path << " (" << ros_bytes.size() << " bytes) vs " << offline_path << " ("
                << offline_bytes.size() << " bytes), first at byte " << at << " (line " << line << "):\n  lockstep: ..."
                << ros_bytes.substr(from, 400) << "...\n  offline:  ..." << offline_bytes.substr(from, 400) << "...";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "sequence_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
