#include "cosmo/ros/frontend_options.hpp"

#include <ros/console.h>
#include <ros/time.h>

#include <stdexcept>

#include "cosmo/common/config_dir.hpp"
#include "cosmo/ros/resolved_sequence.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"

namespace cosmo::ros_glue {

FrontendOptions readFrontendOptions(const ros::NodeHandle& pnh) {
  FrontendOptions o;
  o.robot = nodeRobot(pnh);
  pnh.param<std::string>("config_dir", o.config_dir, cosmo::defaultConfigDir());
  pnh.param<std::string>("odometry", o.odometry, o.odometry);
  pnh.param<std::string>("noise_models", o.noise_models, "");
  pnh.param<std::string>("world_frame", o.world_frame, o.world_frame);
  pnh.param("reference_wait", o.reference_wait, o.reference_wait);
  pnh.param("lockstep", o.lockstep, o.lockstep);
  pnh.param("scan_queue", o.scan_queue, o.scan_queue);
  pnh.param("recorder_wait", o.recorder_wait, o.recorder_wait);
  pnh.param<std::string>("stamp", o.stamp, o.stamp);
  if (o.scan_queue < 1) throw std::runtime_error("~scan_queue must be at least 1, got " + std::to_string(o.scan_queue));
  if (o.stamp != "end" && o.stamp != "start")
    throw std::runtime_error("~stamp must be start or end (the sweep instant of the header stamp), got '" + o.stamp +
                             "'");
  return o;
}

void logFrontendStart(const FrontendOptions& o) {
  ROS_INFO("frontend %c: odometry %s, config %s%s", o.robot, o.odometry.c_str(), o.config_dir.c_str(),
           o.lockstep ? ", lockstep (reference from the player's sequence)" : "");
  if (o.lockstep && !ros::Time::isSimTime())
    ROS_WARN(
        "frontend %c: /use_sim_time was not set when this node started: it runs on this machine's clock, not "
        "the player's /clock (start the base's launch first; the dataset does not depend on it)",
        o.robot);
}

frontend::FrontendParams frontendParams(const FrontendOptions& o) {
  frontend::FrontendParams p = frontend::FrontendParams::loadDir(o.config_dir);
  try {
    p.odometry = frontend::parseOdometryKind(o.odometry);
  } catch (const std::invalid_argument& e) { throw std::runtime_error(std::string("~") + e.what()); }
  return p;
}

frontend::FrontendSetup frontendSetup(const FrontendOptions& o, const frontend::FrontendParams& params,
                                      Trajectory reference, std::size_t first_index) {
  frontend::FrontendSetup setup;
  setup.params = params;
  setup.params.registration = sequenceRegistration(o, params.registration);
  setup.reference = std::move(reference);
  setup.reference_arrival = o.lockstep ? frontend::ReferenceArrival::Whole : frontend::ReferenceArrival::PoseByPose;
  setup.first_index = first_index;
  return setup;
}

std::optional<dataset::NoiseModels> markerNoiseModels(const FrontendOptions& o) {
  if (o.noise_models.empty()) return std::nullopt;
  return cosmo::sequence::loadRunNoiseModels(o.noise_models, "", "", o.config_dir);
}

registration::RegistrationParams sequenceRegistration(const FrontendOptions& o,
                                                      const registration::RegistrationParams& base) {
  const std::optional<ResolvedSequence> sequence = resolvedSequence();
  if (!sequence) return base;
  try {
    registration::RegistrationParams p =
        cosmo::sequence::registrationParamsWith(o.config_dir, sequence->registration, sequence->path);
    if (!sequence->registration.empty())
      ROS_INFO("frontend %c: registration: %s's own keys over %s/registration.yaml", o.robot, sequence->path.c_str(),
               o.config_dir.c_str());
    return p;
  } catch (const std::exception& e) {
    ROS_ERROR("frontend %c: the player's sequence: %s; registration stays %s/registration.yaml's", o.robot, e.what(),
              o.config_dir.c_str());
    return base;
  }
}

std::optional<dataset::NoiseModels> sequenceNoiseModels(const FrontendOptions& o) {
  const std::optional<ResolvedSequence> sequence = resolvedSequence();
  if (!sequence) return std::nullopt;
  try {
    return cosmo::sequence::loadSequenceNoiseModels(sequence->load(), o.config_dir);
  } catch (const std::exception& e) {
    ROS_WARN("frontend %c: no noise models for the loop-closure colours: %s", o.robot, e.what());
    return std::nullopt;
  }
}

}  // namespace cosmo::ros_glue
