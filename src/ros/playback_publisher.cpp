#include "cosmo/ros/playback_publisher.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>

#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

namespace cosmo::ros_glue {

PlaybackPublisher::PlaybackPublisher(ros::NodeHandle& nh, const std::vector<char>& robots, std::string world_frame,
                                     bool points_here, PointTimeEncoding encoding)
    : world_frame_(std::move(world_frame)), encoding_(encoding) {
  clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  progress_pub_ = nh.advertise<std_msgs::String>("/player/progress", 10);
  done_pub_ = nh.advertise<std_msgs::Empty>("/player/done", 1, true);
  sequence_pub_ = nh.advertise<cosmo::TeamSequence>(kTeamSequenceTopic, 1, true);
  for (char r : robots) {
    const std::string ns = std::string("/") + r;
    if (points_here) points_pub_[r] = nh.advertise<sensor_msgs::PointCloud2>(ns + "/points", 5);
    pose_pub_[r] = nh.advertise<geometry_msgs::PoseStamped>(ns + "/reference_pose", 200);
    trajectory_pub_[r] = nh.advertise<cosmo::ReferenceTrajectory>(referenceTrajectoryTopic(r), 1, true);
  }
}

void PlaybackPublisher::announce(const sequence::SequenceConfig& config, const sequence::SequenceTiming& timing,
                                 const std::string& run_id, const std::map<char, Trajectory>& references) {
  cosmo::TeamSequence sequence = teamSequenceToMsg(config, timing);
  sequence.run_id = run_id;
  sequence_pub_.publish(sequence);
  for (auto& [r, pub] : trajectory_pub_) {
    const auto ref = references.find(r);
    pub.publish(trajectoryToMsg(r, ref == references.end() ? Trajectory{} : ref->second, world_frame_));
  }
}

void PlaybackPublisher::clock(StampNs t) {
  rosgraph_msgs::Clock c;
  c.clock = stampToRos(t);
  clock_pub_.publish(c);
}

void PlaybackPublisher::beforeScan(char robot, StampNs stamp, const Trajectory& reference) {
  clock(stamp);
  if (reference.empty()) return;
  for (StampNs s : reference_stream_.beforeScan(robot, reference, stamp)) {
    geometry_msgs::PoseStamped ps;
    ps.header.stamp = stampToRos(s);
    ps.header.frame_id = world_frame_;
    ps.pose = poseToMsg(reference.atClamped(s));
    pose_pub_.at(robot).publish(ps);
  }
  tf_.sendTransform(
      transformMsg(reference.atClamped(stamp), stampToRos(stamp), world_frame_, std::string(1, robot) + "/reference"));
}

void PlaybackPublisher::points(char robot, const Scan& scan) {
  points_pub_.at(robot).publish(toPointCloud2(scan, std::string(1, robot) + "/base_link", encoding_));
}

void PlaybackPublisher::progress(const std::string& line) {
  std_msgs::String s;
  s.data = line;
  progress_pub_.publish(s);
}

void PlaybackPublisher::done() { done_pub_.publish(std_msgs::Empty()); }

bool PlaybackPublisher::referenceHeard(char robot) const { return pose_pub_.at(robot).getNumSubscribers() > 0; }

bool PlaybackPublisher::pointsHeard(char robot) const {
  const auto p = points_pub_.find(robot);
  return p != points_pub_.end() && p->second.getNumSubscribers() > 0;
}

}  // namespace cosmo::ros_glue
