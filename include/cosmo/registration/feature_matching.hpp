#pragma once
// Putative correspondences: nearest neighbours in FPFH space (exact kd-tree search), optionally mutual,
// sorted by feature distance and capped.
#include <cstddef>
#include <vector>

#include "cosmo/registration/point_features.hpp"

namespace cosmo::registration {

struct Correspondence {
  int source = 0;        ///< index into the source feature cloud
  int target = 0;        ///< index into the target feature cloud
  float distance = 0.f;  ///< squared feature distance
};

/// For each source feature its nearest target feature; with `mutual`, kept only if that target's nearest
/// source feature is the same point. Sorted by (distance, source index); at most `max_count`.
/// `eps` > 0 makes the kd-tree search (1+eps)-approximate (faster in 33 dimensions, still deterministic).
std::vector<Correspondence> matchFeatures(const FpfhMatrix& source, const FpfhMatrix& target, std::size_t max_count,
                                          bool mutual = true, float eps = 0.f);

}  // namespace cosmo::registration
