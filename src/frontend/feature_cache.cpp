#include "cosmo/frontend/feature_cache.hpp"

#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <vector>

namespace cosmo::frontend {

namespace {
// Block layout: six uint64 (points, normals, keypoints, feature columns, input_points, downsampled_points), then
// the points, normals (3 floats each), keypoints (int32) and features (33 floats per column, column-major).
constexpr std::size_t kHeader = 6 * sizeof(std::uint64_t);
}  // namespace

std::size_t featureCloudBytes(const registration::FeatureCloud& f) {
  return sizeof(Eigen::Vector3f) * (f.points.size() + f.normals.size()) + sizeof(int) * f.keypoints.size() +
         sizeof(float) * static_cast<std::size_t>(f.features.size());
}

std::vector<char> serializeFeatureCloud(const registration::FeatureCloud& f) {
  const std::uint64_t h[6] = {f.points.size(),    f.normals.size(),
                              f.keypoints.size(), static_cast<std::uint64_t>(f.features.cols()),
                              f.input_points,     f.downsampled_points};
  std::vector<char> out(kHeader + featureCloudBytes(f));
  std::memcpy(out.data(), h, kHeader);
  std::size_t at = kHeader;
  const auto put = [&](const void* p, std::size_t n) {
    if (n > 0) std::memcpy(out.data() + at, p, n);
    at += n;
  };
  put(f.points.data(), sizeof(Eigen::Vector3f) * f.points.size());
  put(f.normals.data(), sizeof(Eigen::Vector3f) * f.normals.size());
  put(f.keypoints.data(), sizeof(int) * f.keypoints.size());
  put(f.features.data(), sizeof(float) * static_cast<std::size_t>(f.features.size()));
  return out;
}

registration::FeatureCloud deserializeFeatureCloud(const std::vector<char>& bytes) {
  if (bytes.size() < kHeader) throw std::runtime_error("feature cache: spilled block too short");
  std::uint64_t h[6];
  std::memcpy(h, bytes.data(), kHeader);
  registration::FeatureCloud f;
  f.points.resize(h[0]);
  f.normals.resize(h[1]);
  f.keypoints.resize(h[2]);
  f.features.resize(registration::kFpfhDim, static_cast<Eigen::Index>(h[3]));
  f.input_points = h[4];
  f.downsampled_points = h[5];
  if (bytes.size() != kHeader + featureCloudBytes(f))
    throw std::runtime_error("feature cache: spilled block of the wrong size");
  std::size_t at = kHeader;
  const auto take = [&](void* p, std::size_t n) {
    if (n > 0) std::memcpy(p, bytes.data() + at, n);
    at += n;
  };
  take(f.points.data(), sizeof(Eigen::Vector3f) * f.points.size());
  take(f.normals.data(), sizeof(Eigen::Vector3f) * f.normals.size());
  take(f.keypoints.data(), sizeof(int) * f.keypoints.size());
  take(f.features.data(), sizeof(float) * static_cast<std::size_t>(f.features.size()));
  return f;
}

std::shared_ptr<const registration::FeatureCloud> FeatureCache::load(const Entry& e) const {
  std::vector<char> block(e.extent.size);
  spill_->read(e.extent, block.data());
  return std::make_shared<const registration::FeatureCloud>(deserializeFeatureCloud(block));
}

std::shared_ptr<const registration::FeatureCloud> FeatureCache::get(const std::shared_ptr<const KeptScan>& scan,
                                                                    const Prepare& prepare) {
  if (!scan) throw std::invalid_argument("feature cache: null scan");
  std::promise<std::shared_ptr<const registration::FeatureCloud>> computed;
  std::shared_future<std::shared_ptr<const registration::FeatureCloud>> waiting;
  bool mine = false;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    auto it = entries_.find(scan.get());
    if (it == entries_.end()) {
      Entry e;
      e.scan = scan;
      e.computing = computed.get_future().share();
      entries_.emplace(scan.get(), std::move(e));
      mine = true;
    } else if (it->second.held) {
      return it->second.held;
    } else if (it->second.spilled) {
      if (auto f = it->second.in_use.lock()) return f;
      std::shared_ptr<const registration::FeatureCloud> f =
          load(it->second);  // under the lock: one copy in memory at a time
      it->second.in_use = f;
      return f;
    } else {
      waiting = it->second.computing;
    }
  }
  if (!mine) return waiting.get();
  std::shared_ptr<const registration::FeatureCloud> features;
  try {
    features = std::make_shared<const registration::FeatureCloud>(prepare(*scan->get()));
    SpillFile::Extent extent;
    if (spill_) {
      const std::vector<char> block = serializeFeatureCloud(*features);
      extent = spill_->append(block.data(), block.size());
    }
    std::lock_guard<std::mutex> lock(mutex_);
    Entry& e = entries_.at(scan.get());
    if (spill_) {
      e.spilled = true;
      e.extent = extent;
      e.in_use = features;
    } else {
      e.held = features;
    }
    e.computing = {};  // callers already waiting hold their own copy of the future
  } catch (...) {
    computed.set_exception(std::current_exception());  // the entry keeps the future: every caller gets the error
    throw;
  }
  computed.set_value(features);
  return features;
}

std::size_t FeatureCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

FeatureCacheFootprint FeatureCache::footprint() const {
  std::lock_guard<std::mutex> lock(mutex_);
  FeatureCacheFootprint f;
  f.entries = entries_.size();
  for (const auto& [key, e] : entries_) {
    if (e.held) f.bytes_in_memory += featureCloudBytes(*e.held);
    if (!e.spilled) continue;
    const std::size_t bytes = e.extent.size - kHeader;
    f.bytes_spilled += bytes;
    if (!e.in_use.expired()) f.bytes_in_memory += bytes;
  }
  return f;
}

}  // namespace cosmo::frontend
