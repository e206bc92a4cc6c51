// gtest node for recorder_write.test: drives the recorder node through its topics and ~write service.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <ros/master.h>
#include <ros/network.h>
#include <xmlrpcpp/XmlRpc.h>

#include <csignal>
#include <cmath>
#include <filesystem>

#include "cosmo/RecorderKeyframe.h"
#include "cosmo/RecorderLoopClosure.h"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"

namespace {

geometry_msgs::Pose pose(double x, double y, double yaw) {
  geometry_msgs::Pose p;
  p.position.x = x;
  p.position.y = y;
  p.orientation.w = std::cos(yaw / 2);
  p.orientation.z = std::sin(yaw / 2);
  return p;
}

// Measurement numbers per sending robot: keyframe i is number i + 1; a robot's loop closure comes after its first
// five keyframes (number 6), a keyframe i >= 5 after it (i + 2).
cosmo::RecorderKeyframe keyframe(char r, unsigned i) {
  cosmo::RecorderKeyframe m;
  m.seq = i < 5 ? i + 1 : i + 2;
  m.header.stamp = ros::Time(1700000000 + i, r == 'b' ? 250000000 : 0);
  m.header.frame_id = "world";
  m.robot = std::string(1, r);
  m.index = i;
  m.odometry_from_previous = pose(1.05, 0, 0);
  m.reference = pose(i + (r == 'b' ? 0.5 : 0.0), r == 'b' ? 2.0 : 0.0, 0);
  m.has_reference = true;
  return m;
}

cosmo::RecorderLoopClosure closure(char owner, double t, char r1, unsigned i1, char r2, unsigned i2,
                                   const geometry_msgs::Pose& m) {
  cosmo::RecorderLoopClosure lc;
  lc.header.stamp = ros::Time(t);
  lc.owner = std::string(1, owner);
  lc.robot1 = std::string(1, r1);
  lc.index1 = i1;
  lc.robot2 = std::string(1, r2);
  lc.index2 = i2;
  lc.measurement = m;
  lc.seq = 6;
  return lc;
}

// Call ~write until the recorder reports `expect` in its counts (messages on several topics arrive in any order).
bool writeWhen(const std::string& expect) {
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::WallTime::now() < until) {
    std_srvs::Trigger srv;
    if (ros::service::call("/recorder/write", srv) && srv.response.success &&
        srv.response.message.find(expect) != std::string::npos)
      return true;
    ros::WallDuration(0.2).sleep();
  }
  return false;
}

// PID of a node through its XML-RPC API (lookupNode at the master, then getPid at the node).
int pidOf(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, true)) return -1;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  if (!client.execute("getPid", request, response) || response.getType() != XmlRpc::XmlRpcValue::TypeArray ||
      response.size() < 3)
    return -1;
  return static_cast<int>(response[2]);
}

}  // namespace

TEST(RecorderNode, WritesOnRequest) {
  ros::NodeHandle nh, pnh("~");
  std::string output;
  ASSERT_TRUE(pnh.getParam("output", output));
  std::map<char, ros::Publisher> kf, lc;
  for (const char r : {'a', 'b'}) {
    kf[r] = nh.advertise<cosmo::RecorderKeyframe>(std::string("/") + r + "/keyframes_meas", 100);
    lc[r] = nh.advertise<cosmo::RecorderLoopClosure>(std::string("/") + r + "/loop_closures", 100);
  }
  ASSERT_TRUE(ros::service::waitForService("/recorder/write", ros::Duration(30.0)));
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(20.0);
  auto connected = [&] {
    for (const char r : {'a', 'b'})
      if (!kf[r].getNumSubscribers() || !lc[r].getNumSubscribers()) return false;
    return true;
  };
  while (!connected() && ros::WallTime::now() < until) ros::WallDuration(0.05).sleep();
  ASSERT_TRUE(connected());

  for (const char r : {'a', 'b'})
    for (unsigned i = 0; i < 5; ++i) kf[r].publish(keyframe(r, i));
  // b3 -> a2: truth (I, [-1.5, -2, 0]); a4 -> a0: gross error (an outlier).
  lc['b'].publish(closure('b', 1700000003.5, 'b', 3, 'a', 2, pose(-1.5, -2.0, 0)));
  lc['a'].publish(closure('a', 1700000004.0, 'a', 4, 'a', 0, pose(-3.0, 1.0, 0.5)));
  ASSERT_TRUE(writeWhen("keyframes a 5 b 5 | loop closures 2"));

  ASSERT_TRUE(std::filesystem::exists(output)) << output;
  ASSERT_TRUE(std::filesystem::exists(cosmo::dataset::DatasetRecorder::metadataPath(output)));
  cosmo::jrl::Dataset ds = cosmo::jrl::readJrl(output);
  for (const auto& v : cosmo::jrl::validate(ds)) ADD_FAILURE() << v.str();
  EXPECT_EQ(ds.name, "recorder_rostest");
  EXPECT_EQ(ds.robots, (std::vector<char>{'a', 'b'}));
  EXPECT_EQ(ds.measurements.at('a').size(), 5u);
  EXPECT_EQ(ds.measurements.at('b').size(), 5u);
  EXPECT_EQ(ds.measurements.at('a')[0].stamp, 1700000000000000000ULL);
  EXPECT_EQ(ds.potential_outliers->at('a').size() + ds.potential_outliers->at('b').size(), 2u);
  EXPECT_EQ(ds.outliers->at('a').size(), 1u);
  EXPECT_EQ(ds.outliers->at('b').size(), 0u);

  // More data: the next write has it.
  kf['a'].publish(keyframe('a', 5));
  ASSERT_TRUE(writeWhen("keyframes a 6 b 5"));
  ds = cosmo::jrl::readJrl(output);
  EXPECT_EQ(ds.measurements.at('a').size(), 6u);

  // Ctrl-C: what arrived before it is written on the way out.
  kf['b'].publish(keyframe('b', 5));
  ros::WallDuration(1.0).sleep();  // delivered (same process pair, one topic)
  const int pid = pidOf("/recorder");
  ASSERT_GT(pid, 0);
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(15.0);
  bool written = false;
  while (!written && ros::WallTime::now() < deadline) {
    ros::WallDuration(0.2).sleep();
    written = cosmo::jrl::readJrl(output).measurements.at('b').size() == 6u;
  }
  EXPECT_TRUE(written) << "the shutdown write did not include keyframe b5";
  // The recorder may still be writing its figures there: a failed removal leaves a temporary folder, not a failure.
  std::error_code ignored;
  if (written) std::filesystem::remove_all(std::filesystem::path(output).parent_path(), ignored);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "recorder_write_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
