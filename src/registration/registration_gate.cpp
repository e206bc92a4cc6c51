#include "cosmo/registration/registration_gate.hpp"

#include "cosmo/registration/global_registration.hpp"

namespace cosmo::registration {

void applyGate(const RegistrationParams& p, RegistrationResult& r) {
  r.valid = false;
  if (r.source_points == 0 || r.target_points == 0) {
    r.reason = "empty cloud after preprocessing";
  } else if (r.correspondences < p.min_correspondences) {
    r.reason = "too few correspondences (" + std::to_string(r.correspondences) + " < " +
               std::to_string(p.min_correspondences) + ")";
  } else if (r.final_inliers < p.min_final_inliers) {
    r.reason =
        "too few final inliers (" + std::to_string(r.final_inliers) + " < " + std::to_string(p.min_final_inliers) + ")";
  } else if (p.min_inlier_ratio > 0.0 &&
             static_cast<double>(r.final_inliers) < p.min_inlier_ratio * static_cast<double>(r.correspondences)) {
    r.reason = "inlier ratio below " + std::to_string(p.min_inlier_ratio);
  } else if (p.min_overlap > 0.0 && r.overlap < p.min_overlap) {
    r.reason = "overlap " + std::to_string(r.overlap) + " below " + std::to_string(p.min_overlap);
  } else if (p.min_structure_overlap > 0.0 && r.structure_overlap < p.min_structure_overlap) {
    r.reason = "structure overlap " + std::to_string(r.structure_overlap) + " below " +
               std::to_string(p.min_structure_overlap);
  } else {
    r.valid = true;
    r.reason = "ok";
  }
}

}  // namespace cosmo::registration
