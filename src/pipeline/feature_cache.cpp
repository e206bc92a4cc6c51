#include "cosmo/pipeline/feature_cache.hpp"

#include <stdexcept>

namespace cosmo::pipeline {

const FeatureCloud& FeatureCache::get(const std::shared_ptr<const Scan>& scan, const Prepare& prepare) {
  if (!scan) throw std::invalid_argument("feature cache: null scan");
  auto it = entries_.find(scan.get());
  if (it == entries_.end()) it = entries_.emplace(scan.get(), std::make_pair(scan, prepare(*scan))).first;
  return it->second.second;
}

}  // namespace cosmo::pipeline
