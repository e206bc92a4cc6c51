#pragma once
// LOAM registration of one scan against another (the target's features as a one-scan map): for keyframe
// pairs, tests and benchmarks.
#include "cosmo/common/scan.hpp"
#include "cosmo/odometry/feature_registration.hpp"
#include "cosmo/odometry/loam_params.hpp"

namespace cosmo {

/// T_target_source (pose of the source sensor in the target sensor frame), starting at `guess`.
RegistrationResult registerScanPair(const Scan& target, const Scan& source, const Pose3& guess,
                                    const LoamParams& params = {});

}  // namespace cosmo
