#include "cosmo/registration/registration_params.hpp"
#include "cosmo/common/param_list.hpp"

#include <stdexcept>

namespace cosmo::registration {

namespace {
void require(bool ok, const ConfigNode& node, const std::string& key, const std::string& what) {
  if (!ok) throw std::runtime_error(node.where + (node.where.empty() ? "" : ".") + key + ": " + what);
}
}  // namespace

RegistrationParams RegistrationParams::fromConfig(const ConfigNode& root) {
  // Accept either the whole file (with a `registration:` section) or the section itself.
  const ConfigNode node = root.has("registration") ? root["registration"] : root;
  RegistrationParams p;
  readParams(node, p);
  require(p.gate == "strict" || p.gate == "paper", node, "gate", "expected strict or paper, got '" + p.gate + "'");
  if (p.gate == "paper") {
    p.min_overlap = 0.0;
    p.min_structure_overlap = 0.0;
  }
  require(p.voxel_size > 0.0, node, "voxel_size", "must be > 0");
  require(p.normal_radius > 0.0, node, "normal_radius", "must be > 0");
  require(p.fpfh_radius > 0.0, node, "fpfh_radius", "must be > 0");
  require(p.noise_bound > 0.0, node, "noise_bound", "must be > 0");
  require(p.max_hypotheses >= 1, node, "max_hypotheses", "must be >= 1");
  require(p.gnc_factor > 1.0, node, "gnc_factor", "must be > 1");
  require(p.max_correspondences > 0, node, "max_correspondences", "must be > 0");
  require(p.max_correspondences <= 20000, node, "max_correspondences", "must be <= 20000 (n^2 graph)");
  return p;
}

}  // namespace cosmo::registration
