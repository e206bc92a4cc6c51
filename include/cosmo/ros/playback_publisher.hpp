#pragma once
// What the player publishes around the scans, in one place: /clock, the sequence (/player/sequence and each
// robot's reference trajectory, latched), each robot's reference poses up to a scan (about every 20 ms,
// sequence/reference_stream.hpp) and its TF, the scans' points when the trials are read here, /player/progress
// and /player/done.
#include <map>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/sequence/reference_stream.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"

namespace cosmo::ros_glue {

class PlaybackPublisher {
 public:
  /// `points_here`: this node publishes each robot's /<r>/points (else the robots' trial players do), with the
  /// per-point times in `encoding`.
  PlaybackPublisher(ros::NodeHandle& nh, const std::vector<char>& robots, std::string world_frame, bool points_here,
                    PointTimeEncoding encoding);

  /// The sequence with its run id and every robot's reference trajectory (latched).
  void announce(const sequence::SequenceConfig& config, const sequence::SequenceTiming& timing,
                const std::string& run_id, const std::map<char, Trajectory>& references);
  void clock(StampNs t);
  /// The clock at the scan, then `robot`'s reference poses up to it and its TF (none without a reference).
  void beforeScan(char robot, StampNs stamp, const Trajectory& reference);
  /// The scan's points on /<robot>/points.
  void points(char robot, const Scan& scan);
  void progress(const std::string& line);
  void done();
  /// Someone listens to `robot`'s reference poses / points (the player's link check of its front-end).
  bool referenceHeard(char robot) const;
  bool pointsHeard(char robot) const;

 private:
  std::string world_frame_;
  PointTimeEncoding encoding_;
  sequence::ReferenceStream reference_stream_;
  ros::Publisher clock_pub_, progress_pub_, done_pub_, sequence_pub_;
  std::map<char, ros::Publisher> points_pub_, pose_pub_, trajectory_pub_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace cosmo::ros_glue
