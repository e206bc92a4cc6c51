#include "cosmo/ros/comm_broker_options.hpp"

#include <ros/console.h>

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "cosmo/comm/comm_model.hpp"
#include "cosmo/comm/radio_status.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/ros/robot_list.hpp"

namespace cosmo::ros_glue {

comm::RadioParams readRadioParams(const ros::NodeHandle& pnh) {
  std::string comm = "wifi", config, size_model, timeout_mode;
  pnh.param<std::string>("comm", comm, comm);
  pnh.param<std::string>("config", config, "");
  comm::RadioParams params = comm::resolveCommModel(config.empty() ? comm : config, "").params;
  if (pnh.getParam("size_model", size_model)) params.size_model = comm::sizeModelFromString(size_model, "~size_model");
  if (pnh.getParam("timeout_mode", timeout_mode))
    params.timeout_mode = comm::timeoutModeFromString(timeout_mode, "~timeout_mode");
  std::string trace;
  if (pnh.getParam("trace", trace) && !trace.empty())
    params.trace = std::make_shared<const comm::RadioTrace>(comm::RadioTrace::read(trace));
  return params;
}

CommBrokerOptions readCommBrokerOptions(const ros::NodeHandle& pnh) {
  CommBrokerOptions o;
  o.robots = ros_glue::readTeamRobots(pnh);
  o.radio = readRadioParams(pnh);
  pnh.param("seed", o.seed, 0);
  pnh.param("xz_preset", o.xz_preset, 6);
  if (o.xz_preset < 0 || o.xz_preset > 9) throw std::runtime_error("~xz_preset: must be in 0..9");
  pnh.param<std::string>("log_file", o.log_file, "");
  pnh.param<std::string>("frame_id", o.frame_id, "world");
  pnh.param("compress_payload", o.compress, true);
  if (!o.compress && o.radio.size_model == comm::RadioParams::SizeModel::RealCompressed) {
    ROS_WARN("comm_broker: ~compress_payload false ignored: the real size model needs the xz payload");
    o.compress = true;
  }
  pnh.param("lockstep", o.lockstep, false);
  return o;
}

void logCommBrokerStart(const CommBrokerOptions& o) {
  const comm::RadioParams& p = o.radio;
  ROS_INFO(
      "comm_broker: %zu robots, B %.0f kB/s, d_init %.0f m, d_intf %.0f m, P_max %.2f, seed %s, sizes %s, "
      "timeout %s%s",
      o.robots.size(), p.bandwidth_kBps, p.d_init, p.d_intf, p.p_max,
      o.lockstep ? "from the sequence" : std::to_string(o.seed).c_str(), toString(p.size_model).c_str(),
      toString(p.timeout_mode).c_str(), o.lockstep ? ", lockstep (driven by the player)" : "");
}

std_msgs::String offeredMsg(const std::map<char, std::uint32_t>& next_index) {
  nlohmann::json next = nlohmann::json::object();
  for (const auto& [r, n] : next_index) next[std::string(1, r)] = n;
  std_msgs::String m;
  m.data = next.dump();
  return m;
}

std_msgs::String radioStatsMsg(const comm::RadioSimulator& radio, double time) {
  std_msgs::String m;
  m.data = radioStatus(radio, time).dump();
  return m;
}

void TransferLogFile::write(const comm::RadioSimulator& radio) const {
  if (path_.empty()) return;
  try {
    writeTransferLog(path_, radio);
  } catch (const std::exception& e) { ROS_ERROR("comm_broker: %s", e.what()); }
}

void TransferLogFile::writeEvery30s(const comm::RadioSimulator& radio, double radio_time) {
  if (path_.empty() || radio_time - last_write_ < 30.0) return;
  last_write_ = radio_time;
  try {
    writeTransferLog(path_, radio);
  } catch (const std::exception& ex) { ROS_ERROR_THROTTLE(30.0, "comm_broker: %s", ex.what()); }
}

}  // namespace cosmo::ros_glue
