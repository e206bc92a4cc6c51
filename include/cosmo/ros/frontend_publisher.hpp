#pragma once
// What the front-end node publishes of its front-end's steps (frontend::RobotFrontend::add), in one place:
//   an own scan   TF <r>/odom -> <r>/base_link (its odometry) and world -> <r>/odom (the map's alignment); a keyframe
//                 to the recorder (numbered, kept until acknowledged: RecorderLink) and offered to the teammates
//                 (keyframe_scans);
//   a closure     completed in order; an accepted one to the recorder; every one on the map (markers);
//   an ack        (cosmo/FrontendAck) after every scan and delivery: what it processed, sent and skipped.
#include <cstdint>
#include <optional>
#include <string>

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "cosmo/Keyframe.h"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/frontend/frontend_map.hpp"
#include "cosmo/frontend/robot_frontend.hpp"
#include "cosmo/ros/recorder_link.hpp"

namespace cosmo::ros_glue {

class FrontendPublisher {
 public:
  /// `recorder`: the node's link to the recorder (it decides the numbering before the front-end is built).
  FrontendPublisher(ros::NodeHandle& nh, char robot, std::string world_frame, RecorderLink& recorder,
                    std::optional<dataset::NoiseModels> noise);

  /// An own scan's step, published at `stamp`; `scans_skipped`: the robot's count so far (in its keyframe).
  void ownScan(frontend::RobotFrontend& frontend, const frontend::Step& step, const ros::Time& stamp,
               std::uint32_t scans_skipped);
  /// A teammate scan's step; `offer`: its message (the teammate keyframe's reference pose, when it has one).
  void teammateScan(frontend::RobotFrontend& frontend, const frontend::Step& step, const cosmo::Keyframe& offer);
  /// The ack at `stamp` (`frontend` nullptr: none built yet).
  void ack(const frontend::RobotFrontend* frontend, StampNs stamp, std::size_t received_dropped, std::size_t queued,
           std::uint32_t scans_skipped);

  /// The end-of-run line on stdout: scans processed and `skipped`, the `peak_waiting` scans, keyframes,
  /// measurements sent and not acknowledged, peak memory (docs/benchmarks.md).
  void summary(const frontend::RobotFrontend* frontend, std::uint32_t skipped, std::size_t peak_waiting) const;

  /// The markers' labels, when they are known only later (lockstep: the player's sequence).
  frontend::FrontendMap& map() { return map_; }

 private:
  void closures(frontend::RobotFrontend& frontend, const frontend::Step& step);
  void markers(const ros::Time& stamp);

  char robot_;
  std::string world_frame_, odom_frame_, base_frame_;
  RecorderLink& recorder_;
  frontend::FrontendMap map_;
  std::size_t loop_closures_published_ = 0;  ///< counted in the ack (the player's end-of-run handshake)
  ros::Publisher offer_pub_, ack_pub_, marker_pub_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace cosmo::ros_glue
