#pragma once
// What a front-end's map display shows (the frontend node's rviz markers), without ROS: its keyframe trajectory in
// the world frame and its loop closures as segments between the two keyframes, each with its label
// (closure_label.hpp). A keyframe's world position is its reference pose, else its odometry pose moved by the
// odometry-to-world alignment (the reference of its first keyframe times its odometry pose^-1; identity without
// one).
// Teammates' keyframes are known by the reference poses their delivered scans carry.
#include <cstddef>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cosmo/frontend/closure_label.hpp"
#include "cosmo/frontend/robot_frontend.hpp"

namespace cosmo::frontend {

/// A loop closure as shown: between the world positions of its two keyframes.
struct ClosureSegment {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
  ClosureLabel label = ClosureLabel::Unlabelled;
};

class FrontendMap {
 public:
  /// `noise`: the noise models the labels use (none: accepted closures are unlabelled).
  explicit FrontendMap(char robot, std::optional<dataset::NoiseModels> noise = std::nullopt);

  /// One of the robot's own keyframes.
  void addKeyframe(const KeyframeRecord& keyframe);
  /// A teammate's keyframe, delivered with its reference pose.
  void addTeammateKeyframe(char robot, std::size_t index, const Pose3& reference);
  /// A loop-closure attempt (accepted or not), labelled now.
  void addClosure(const LoopClosureAttempt& attempt);

  bool hasNoiseModels() const { return labeller_.hasNoiseModels(); }
  /// Noise models known only later (a lockstep front-end learns its sequence from the player).
  void setNoiseModels(dataset::NoiseModels noise) { labeller_.setNoiseModels(std::move(noise)); }

  /// The odometry frame in the world frame.
  const Pose3& worldFromOdometry() const { return world_T_odom_; }
  /// The world positions of the robot's keyframes, in order.
  const std::vector<Eigen::Vector3d>& trajectory() const { return trajectory_; }
  /// The loop closures whose two keyframes have a position, in the order they came.
  std::vector<ClosureSegment> closures() const;

 private:
  struct Closure {
    std::pair<char, std::size_t> a, b;
    ClosureLabel label;
  };

  char robot_;
  ClosureLabeller labeller_;
  Pose3 world_T_odom_ = Pose3::Identity();
  std::map<std::pair<char, std::size_t>, Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector3d> trajectory_;
  std::vector<Closure> closures_;
};

}  // namespace cosmo::frontend
