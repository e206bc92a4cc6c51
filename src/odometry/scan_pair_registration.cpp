#include "cosmo/odometry/scan_pair_registration.hpp"

#include "cosmo/odometry/feature_extraction.hpp"
#include "cosmo/odometry/local_feature_map.hpp"
#include "cosmo/odometry/scan_lines.hpp"

namespace cosmo {

RegistrationResult registerScanPair(const Scan& target, const Scan& source, const Pose3& guess,
                                    const LoamParams& params) {
  const LoamFeatures ft = extractFeatures(organizeScanLines(target, params), params);
  const LoamFeatures fs = extractFeatures(organizeScanLines(source, params), params);
  LocalFeatureMap map(1);
  map.add(ft.edge_points, ft.planar_points);
  return registerFeatures(fs, map, guess, params, std::nullopt);
}

}  // namespace cosmo
