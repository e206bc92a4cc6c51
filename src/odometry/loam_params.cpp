#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/common/param_list.hpp"

namespace cosmo::odometry {

LoamParams LoamParams::fromConfig(const ConfigNode& root) {
  const ConfigNode c = root.has("odometry") ? root["odometry"] : root;
  LoamParams p;
  readParams(c, p);
  return p;
}

}  // namespace cosmo::odometry
