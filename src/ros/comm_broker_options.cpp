#include "cosmo/ros/comm_broker_options.hpp"

#include <ros/console.h>

#include <stdexcept>

#include "cosmo/comm/comm_model.hpp"
#include "cosmo/comm/radio_trace.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/ros/robot_list.hpp"

namespace cosmo::ros_glue {

RadioParams readRadioParams(const ros::NodeHandle& pnh) {
  std::string comm = "wifi", config, size_model, timeout_mode;
  pnh.param<std::string>("comm", comm, comm);
  pnh.param<std::string>("config", config, "");
  RadioParams params = resolveCommModel(config.empty() ? comm : config, "").params;
  if (pnh.getParam("size_model", size_model)) params.size_model = sizeModelFromString(size_model, "~size_model");
  if (pnh.getParam("timeout_mode", timeout_mode))
    params.timeout_mode = timeoutModeFromString(timeout_mode, "~timeout_mode");
  std::string trace;
  if (pnh.getParam("trace", trace) && !trace.empty())
    params.trace = std::make_shared<const RadioTrace>(RadioTrace::read(trace));
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
  if (!o.compress && o.radio.size_model == RadioParams::SizeModel::RealCompressed) {
    ROS_WARN("comm_broker: ~compress_payload false ignored: the real size model needs the xz payload");
    o.compress = true;
  }
  pnh.param("lockstep", o.lockstep, false);
  return o;
}

}  // namespace cosmo::ros_glue
