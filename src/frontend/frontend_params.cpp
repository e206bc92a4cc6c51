#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/common/param_list.hpp"

#include <filesystem>
#include <stdexcept>

namespace cosmo::frontend {

FrontendParams FrontendParams::fromConfig(const ConfigNode& node) {
  const ConfigNode n = node.has("frontend") ? node["frontend"] : node;
  FrontendParams p;
  readParams(n, p);
  if (!(p.keyframe_distance > 0.0)) throw std::runtime_error(n["keyframe_distance"].where + ": must be > 0");
  if (!(p.keyframe_min_range >= 0.0)) throw std::runtime_error(n["keyframe_min_range"].where + ": must be >= 0");
  if (!(p.reference_tolerance_s >= 0.0)) throw std::runtime_error(n["reference_tolerance_s"].where + ": must be >= 0");
  return p;
}

FrontendParams FrontendParams::loadDir(const std::string& dir) {
  namespace fs = std::filesystem;
  auto file = [&](const char* name) { return (fs::path(dir) / name).string(); };
  FrontendParams p;
  if (fs::exists(file("frontend.yaml"))) p = fromConfig(ConfigNode::load(file("frontend.yaml")));
  if (fs::exists(file("odometry.yaml")))
    p.loam = odometry::LoamParams::fromConfig(ConfigNode::load(file("odometry.yaml")));
  if (fs::exists(file("place_recognition.yaml")))
    p.place = place_recognition::PlaceRecognitionParams::fromConfig(ConfigNode::load(file("place_recognition.yaml")));
  if (fs::exists(file("registration.yaml")))
    p.registration = registration::RegistrationParams::fromConfig(ConfigNode::load(file("registration.yaml")));
  return p;
}

}  // namespace cosmo::frontend
