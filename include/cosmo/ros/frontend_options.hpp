#pragma once
// The frontend node's parameters (docs/nodes.md), read and checked, and the parameters and noise models the node's
// front-end is built with: config_dir's, with the odometry ~odometry names and the registration keys of the
// player's sequence (resolved_sequence.hpp) over config_dir's.
#include <optional>
#include <string>

#include <ros/node_handle.h>

#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/frontend/robot_frontend.hpp"

namespace cosmo::ros_glue {

struct FrontendOptions {
  char robot = 'a';
  std::string config_dir, odometry = "loam", noise_models, world_frame = "world", stamp = "end";
  double reference_wait = 0.5, recorder_wait = 10.0;
  int scan_queue = 10;
  bool lockstep = false;
};

/// The node's first log lines: its odometry and config; in lockstep, a warning when /use_sim_time is not set.
void logFrontendStart(const FrontendOptions& o);
/// Every parameter; throws std::runtime_error naming the one that is out of range.
FrontendOptions readFrontendOptions(const ros::NodeHandle& pnh);
/// config_dir's front-end parameters with the odometry ~odometry names (frontend::OdometrySource).
frontend::FrontendParams frontendParams(const FrontendOptions& o);
/// What the node's front-end is built with: `params` with the player's sequence's registration keys
/// (sequenceRegistration), `reference` known whole (lockstep: the sequence's) or arriving pose by pose (real time,
/// frontend::OdometrySource states both rules), keyframes numbered from `first_index` (a restart continues its
/// robot's).
frontend::FrontendSetup frontendSetup(const FrontendOptions& o, const frontend::FrontendParams& params,
                                      Trajectory reference, std::size_t first_index);
/// ~noise_models for the loop-closure colours; none: unlabelled (lockstep: the sequence's, once it is known).
std::optional<dataset::NoiseModels> markerNoiseModels(const FrontendOptions& o);
/// `base` with the player's sequence's own registration keys over config_dir's registration.yaml, logged; `base`
/// when no sequence was announced or its keys cannot be read (logged).
registration::RegistrationParams sequenceRegistration(const FrontendOptions& o,
                                                      const registration::RegistrationParams& base);
/// The noise models the player's sequence labels with (the recorder's), for the markers' colours; none when no
/// sequence was announced or they cannot be loaded (logged).
std::optional<dataset::NoiseModels> sequenceNoiseModels(const FrontendOptions& o);

}  // namespace cosmo::ros_glue
