#include "cosmo/pipeline/feature_cache.hpp"

#include <exception>
#include <stdexcept>

namespace cosmo::pipeline {

const FeatureCloud& FeatureCache::get(const std::shared_ptr<const Scan>& scan, const Prepare& prepare) {
  if (!scan) throw std::invalid_argument("feature cache: null scan");
  std::promise<FeatureCloud> computed;
  std::shared_future<FeatureCloud> features;
  bool mine = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = entries_.find(scan.get());
    if (it == entries_.end()) {
      features = computed.get_future().share();
      entries_.emplace(scan.get(), Entry{scan, features});
      mine = true;
    } else {
      features = it->second.features;
    }
  }
  if (mine) {
    try {
      computed.set_value(prepare(*scan));
    } catch (...) {
      computed.set_exception(std::current_exception());
    }
  }
  return features.get();  // the shared state lives as long as the entry
}

std::size_t FeatureCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

}  // namespace cosmo::pipeline
