#pragma once
// Global (initial-guess-free) registration of a loop-closure scan pair in the manner of KISS-Matcher:
// voxel downsampling -> normals -> FPFH -> mutual-NN correspondences (capped) -> pairwise-consistency graph ->
// max k-core / max clique -> GNC-TLS rotation + TLS translation -> optional point-to-plane ICP -> validity gate.
// When the gate rejects the solution of the maximum clique, the next clique (after removing the correspondences
// that solution explains) is solved and verified, up to max_hypotheses; the first one the gate accepts (else
// the one with the largest overlap) is reported. Repetitive or symmetric scenes (a street seen from the
// opposite direction) give a wrong largest clique whose solution overlaps poorly.
// The gate looks only at the registration's own evidence (inlier counts, the overlap of the source with the
// target at the solution, and that overlap over the source's structure points, i.e. without ground), never at
// a reference pose: a wrong loop closure it accepts is a realistic outlier.
#include <cstddef>
#include <string>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/registration/feature_cloud.hpp"
#include "cosmo/registration/registration_params.hpp"
#include "cosmo/registration/stage_observer.hpp"

namespace cosmo::registration {

struct RegistrationResult {
  Pose3 T_target_source = Pose3::Identity();  ///< maps source points into the target frame
  std::size_t source_points = 0;              ///< feature points of the source (downsampled, with a normal)
  std::size_t target_points = 0;              ///< same for the target
  std::size_t source_keypoints = 0;           ///< source points carrying an FPFH feature (keypoint subsampling)
  std::size_t target_keypoints = 0;           ///< same for the target
  std::size_t correspondences = 0;            ///< mutual-NN correspondences after the cap
  std::size_t max_core_size = 0;              ///< vertices of the max k-core of the consistency graph
  std::size_t pruned_inliers = 0;             ///< correspondences surviving the pruning (max clique / k-core)
  std::size_t final_inliers = 0;              ///< pruned correspondences within noise_bound of the final transform
  bool clique_proven = true;                  ///< false when the max-clique search hit its node budget
  int hypotheses = 0;                         ///< cliques solved and verified (more than 1 when the first was rejected)
  int hypothesis = 0;                         ///< index of the one reported (0 = the maximum clique)
  bool refined = false;                       ///< the ICP refinement was applied
  double overlap = 0.0;                       ///< fraction of source points with a target point within icp_max_distance
                                              ///< at the reported transform
  double structure_overlap = 0.0;             ///< the same over the source's structure points (|normal z| below
                                   ///< structure_max_normal_z): ground, which matches almost anywhere, left out
  bool valid = false;  ///< the gate's verdict
  std::string reason;  ///< why it was rejected (or "ok")
};

class GlobalRegistration {
 public:
  explicit GlobalRegistration(const RegistrationParams& p = {});

  /// Register `source` to `target` (both in their own sensor frames).
  RegistrationResult align(const Scan& source, const Scan& target) const;
  /// The same with stage notifications (for timing by tools/benchmarks).
  RegistrationResult align(const Scan& source, const Scan& target, StageObserver* observer) const;
  /// Per-scan half, cacheable per keyframe.
  FeatureCloud prepare(const Scan& scan, StageObserver* observer = nullptr) const;
  /// Pairwise half on prepared clouds.
  RegistrationResult align(const FeatureCloud& source, const FeatureCloud& target,
                           StageObserver* observer = nullptr) const;

  const RegistrationParams& params() const { return params_; }

 private:
  RegistrationParams params_;
};

}  // namespace cosmo::registration
