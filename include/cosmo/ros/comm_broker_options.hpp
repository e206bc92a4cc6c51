#pragma once
// The comm_broker node's parameters (see src/nodes/comm_broker.cpp for their meaning), read and checked.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <std_msgs/String.h>

#include <ros/node_handle.h>

#include "cosmo/comm/radio_params.hpp"
#include "cosmo/comm/radio_simulator.hpp"

namespace cosmo::ros_glue {

struct CommBrokerOptions {
  std::vector<char> robots;
  comm::RadioParams radio;
  int seed = 0, xz_preset = 6;
  std::string log_file, frame_id = "world";
  bool compress = true, lockstep = false;
};

/// The radio's parameters: ~comm (wifi | proradio) or ~config (a config/comm/*.yaml, wins), then ~size_model,
/// ~timeout_mode and ~trace (a radio trace CSV, comm/radio_trace.hpp; wins over the config's) when set.
comm::RadioParams readRadioParams(const ros::NodeHandle& pnh);
/// Every parameter; throws std::runtime_error naming the one that is out of range.
CommBrokerOptions readCommBrokerOptions(const ros::NodeHandle& pnh);

/// The node's first log line: the robots, the radio's parameters, the seed and the mode.
void logCommBrokerStart(const CommBrokerOptions& o);

/// /comm/offered: per robot, where a restarted front-end continues its keyframe indices (JSON {"a": n, ...}).
std_msgs::String offeredMsg(const std::map<char, std::uint32_t>& next_index);

/// /comm/stats: the radio's status at `time` (comm/radio_status.hpp) as JSON.
std_msgs::String radioStatsMsg(const comm::RadioSimulator& radio, double time);

/// The transfer log at ~log_file (CSV + summary, comm/transfer_log.hpp; none when empty): written at the end and
/// rewritten whenever 30 s of radio time passed since the last write. A failed write is logged, never thrown.
class TransferLogFile {
 public:
  explicit TransferLogFile(std::string path) : path_(std::move(path)) {}
  void write(const comm::RadioSimulator& radio) const;
  void writeEvery30s(const comm::RadioSimulator& radio, double radio_time);

 private:
  std::string path_;
  double last_write_ = 0.0;
};

}  // namespace cosmo::ros_glue
