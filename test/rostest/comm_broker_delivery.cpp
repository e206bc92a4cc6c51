// gtest node for comm_broker_delivery.test: drives /clock, places robots a, b 5 m apart and c, d 500 m apart,
// offers keyframes, and checks what arrives on /<r>/received_scans.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "cosmo/Keyframe.h"
#include "cosmo/ros/point_cloud.hpp"

namespace {

cosmo::Scan makeScan(char robot, int index) {
  cosmo::Scan s;
  for (int i = 0; i < 3000; ++i) {
    const float a = 0.002f * static_cast<float>(i) * static_cast<float>(robot) + static_cast<float>(index);
    s.points.emplace_back(10.0f * std::cos(a), 10.0f * std::sin(a), 0.001f * static_cast<float>(i % 97));
  }
  return s;
}

TEST(CommBroker, FarScansNeverDeliveredCloseOnesAre) {
  ros::NodeHandle nh;
  const std::string robots = "abcd";
  const std::map<char, std::pair<double, double>> where = {
      {'a', {0, 0}}, {'b', {5, 0}}, {'c', {0, 1000}}, {'d', {500, 1000}}};
  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  std::map<char, ros::Publisher> pose_pub, kf_pub;
  std::map<char, std::vector<cosmo::Keyframe>> received;
  std::vector<ros::Subscriber> subs;
  for (char r : robots) {
    const std::string ns = std::string("/") + r;
    pose_pub[r] = nh.advertise<geometry_msgs::PoseStamped>(ns + "/reference_pose", 10);
    kf_pub[r] = nh.advertise<cosmo::Keyframe>(ns + "/keyframe_scans", 100);
    subs.push_back(nh.subscribe<cosmo::Keyframe>(
        ns + "/received_scans", 100,
        [&received, r](const cosmo::Keyframe::ConstPtr& m) { received[r].push_back(*m); }));
  }
  std::string last_stats;
  bool saw_link = false;
  subs.push_back(nh.subscribe<std_msgs::String>("/comm/stats", 10,
                                                [&](const std_msgs::String::ConstPtr& m) { last_stats = m->data; }));
  subs.push_back(nh.subscribe<visualization_msgs::MarkerArray>(
      "/comm/links", 10, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        for (const auto& mk : m->markers)
          if (mk.action == visualization_msgs::Marker::ADD && !mk.points.empty()) saw_link = true;
      }));

  // Wait for the broker to connect (wall clock: sim time does not run yet).
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  auto connected = [&] {
    for (char r : robots)
      if (kf_pub[r].getNumSubscribers() == 0 || pose_pub[r].getNumSubscribers() == 0) return false;
    for (const auto& s : subs)
      if (s.getNumPublishers() == 0) return false;
    return clock_pub.getNumSubscribers() > 0;
  };
  while (!connected() && ros::WallTime::now() < deadline) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(connected()) << "comm_broker did not connect";

  const int kOffers = 3;
  double t = 100.0;
  for (int i = 0; i < 1500; ++i, t += 0.02) {
    rosgraph_msgs::Clock c;
    c.clock.fromSec(t);
    clock_pub.publish(c);
    for (char r : robots) {
      geometry_msgs::PoseStamped p;
      p.header.stamp = c.clock;
      p.header.frame_id = "world";
      p.pose.position.x = where.at(r).first;
      p.pose.position.y = where.at(r).second;
      p.pose.orientation.w = 1.0;
      pose_pub[r].publish(p);
    }
    if (i == 20) {
      for (char r : robots)
        for (int k = 0; k < kOffers; ++k) {
          cosmo::Keyframe m;
          m.header.stamp = c.clock;
          m.header.frame_id = std::string(1, r) + "/os_sensor";
          m.robot = std::string(1, r);
          m.index = k;
          m.cloud = cosmo::ros_glue::toPointCloud2(makeScan(r, k), m.header.frame_id);
          kf_pub[r].publish(m);
        }
    }
    ros::spinOnce();
    ros::WallDuration(0.004).sleep();
    if (i > 200 && received['a'].size() == kOffers && received['b'].size() == kOffers && i > 1000) break;
  }
  for (int i = 0; i < 20; ++i) {
    ros::spinOnce();
    ros::WallDuration(0.02).sleep();
  }

  EXPECT_TRUE(received['c'].empty()) << "c is 500 m from d: nothing may arrive";
  EXPECT_TRUE(received['d'].empty());
  for (char r : {'a', 'b'}) {
    const char other = r == 'a' ? 'b' : 'a';
    ASSERT_EQ(received[r].size(), static_cast<std::size_t>(kOffers)) << "robot " << r;
    std::set<std::uint32_t> indices;
    for (const cosmo::Keyframe& m : received[r]) {
      EXPECT_EQ(m.sender, std::string(1, other));
      EXPECT_EQ(m.robot, std::string(1, other));
      indices.insert(m.index);
      const cosmo::Scan got = cosmo::ros_glue::fromPointCloud2(m.cloud);
      const cosmo::Scan want = makeScan(other, static_cast<int>(m.index));
      ASSERT_EQ(got.size(), want.size());
      for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got.points[i], want.points[i]);
      EXPECT_EQ(m.header.frame_id, std::string(1, other) + "/os_sensor");
    }
    EXPECT_EQ(indices.size(), static_cast<std::size_t>(kOffers)) << "duplicate delivery to " << r;
  }
  ASSERT_FALSE(last_stats.empty());
  const auto stats = nlohmann::json::parse(last_stats);
  EXPECT_EQ(stats["delivered"].get<int>(), 2 * kOffers);
  EXPECT_EQ(stats["pending"]["c->d"].get<int>(), kOffers);
  EXPECT_TRUE(saw_link);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "comm_broker_delivery");
  ros::NodeHandle nh;  // keep the node alive
  return RUN_ALL_TESTS();
}
