#pragma once
// The comm_broker node's parameters (see src/nodes/comm_broker.cpp for their meaning), read and checked.
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "cosmo/comm/radio_params.hpp"

namespace cosmo::ros_glue {

struct CommBrokerOptions {
  std::vector<char> robots;
  RadioParams radio;
  int seed = 0, xz_preset = 6;
  std::string log_file, frame_id = "world";
  bool compress = true, lockstep = false;
};

/// The radio's parameters: ~comm (wifi | proradio) or ~config (a config/comm/*.yaml, wins), then ~size_model,
/// ~timeout_mode and ~trace (a radio trace CSV, comm/radio_trace.hpp; wins over the config's) when set.
RadioParams readRadioParams(const ros::NodeHandle& pnh);
/// Every parameter; throws std::runtime_error naming the one that is out of range.
CommBrokerOptions readCommBrokerOptions(const ros::NodeHandle& pnh);

}  // namespace cosmo::ros_glue
