#include "cosmo/trials/bag_scan_source.hpp"

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "cosmo/cache/cache.hpp"
#include "cosmo/sequence/trial_coverage.hpp"
#include "cosmo/trials/bag_format.hpp"
#include "cosmo/trials/scan_cache.hpp"
#include "cosmo/trials/trial_reference.hpp"

namespace cosmo::trials {

namespace {

/// What a scan-cache entry holds, as `cosmo_cache` lists it.
std::string cacheInfo(const sequence::TrialConfig& trial) {
  return "trial " + trial.name + ": " + std::filesystem::absolute(trial.bag).string() + " " + trial.topic +
         (trial.stamp_at_end ? "" : " (stamps at sweep start)");
}

}  // namespace

std::unique_ptr<trials::TrialScanSource> openTrialScanSource(const sequence::TrialConfig& trial) {
  if (trials::detectBagFormat(trial.bag) == trials::BagFormat::Ros1) {
    // By value: a cached source that finds its cache damaged decodes the bag later.
    auto decode = [bag = trial.bag, topic = trial.topic,
                   at_end = trial.stamp_at_end]() -> std::unique_ptr<trials::TrialScanSource> {
      return std::make_unique<trials::Ros1ScanSource>(bag, topic, at_end);
    };
    // Compressed chunks (MCD: bz2) are decompressed once: later runs read the decoded scans.
    const std::string cache_dir = trials::scanCacheDir();
    if (!cache_dir.empty() && trials::ros1ChunksCompressed(trial.bag)) {
      return trials::openCachedScans(trials::scanCachePath(cache_dir, trial.bag, trial.topic, trial.stamp_at_end),
                                     decode, cacheInfo(trial));
    }
    return decode();
  }
  return std::make_unique<trials::Ros2ScanSource>(trial.bag, trial.topic, trial.stamp_at_end);
}

sequence::TrialSpan readTrialSpan(const sequence::TrialConfig& trial) {
  // A run asks for each trial's span more than once (the pre-flight check, the synchronization): it is read once
  // per process, and for a ROS 1 bag with compressed chunks kept beside its scan cache, so that a later run
  // decompresses none of it.
  static std::mutex mutex;
  static std::map<std::string, std::pair<StampNs, StampNs>> known;
  namespace fs = std::filesystem;
  const std::string key = fs::absolute(trial.bag).string() + "\n" + trial.topic + "\n" +
                          std::to_string(fs::last_write_time(trial.bag).time_since_epoch().count()) + "\n" +
                          std::to_string(fs::is_regular_file(trial.bag) ? fs::file_size(trial.bag) : 0);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = known.find(key); it != known.end()) return {trial.robot, it->second.first, it->second.second};
  }
  sequence::TrialSpan span;
  if (trials::detectBagFormat(trial.bag) == trials::BagFormat::Ros1) {
    const std::string cache_dir = trials::scanCacheDir();
    const bool cached = !cache_dir.empty() && trials::ros1ChunksCompressed(trial.bag);
    const std::string path = cached ? trials::scanSpanPath(cache_dir, trial.bag, trial.topic, trial.stamp_at_end) : "";
    span.robot = trial.robot;
    if (!cached || !trials::readCachedSpan(path, span.first, span.last)) {
      span = trials::readRos1TrialSpan(trial.bag, trial.topic, trial.robot);
      if (cached) {
        trials::writeCachedSpan(path, span.first, span.last);
        cache::writeInfo(cache::infoPathOf(path), cacheInfo(trial));
      }
    }
  } else {
    span = trials::readRos2TrialSpan(trial.bag, trial.topic, trial.robot);
  }
  std::lock_guard<std::mutex> lock(mutex);
  known[key] = {span.first, span.last};
  return span;
}

sequence::TrialSpan readSweepEndSpan(const sequence::TrialConfig& trial) {
  sequence::TrialSpan span = readTrialSpan(trial);
  if (trial.stamp_at_end) return span;
  // Header stamps at the sweep start: the decoded scans are stamped at its end; every sweep lasts as the first.
  Scan first;
  if (openTrialScanSource(trial)->next(first) && first.stamp > span.first) {
    const StampNs sweep = first.stamp - span.first;
    span.first += sweep;
    span.last += sweep;
  }
  return span;
}

sequence::TrialBasis readTrialBasis(const sequence::TrialConfig& trial) {
  sequence::TrialBasis basis;
  basis.body_reference = trials::readBodyReference(trial);
  basis.span = sequence::TrialCoverage(trial.name, basis.body_reference).clip(readSweepEndSpan(trial));
  return basis;
}

std::string trialDewarpOff(const sequence::TrialConfig& trial) {
  const std::unique_ptr<TrialScanSource> source = openTrialScanSource(trial);
  Scan first;
  if (!source->next(first) || first.hasTime()) return "";
  const std::string fields = describeFields(source->lastLayout());  // a cached scan's layout is not kept
  return "its clouds carry no per-point time" + (fields.empty() ? std::string() : " (fields " + fields + ")") +
         ": its sweeps are not dewarped";
}

sequence::SequenceTiming synchronizeSequence(const sequence::SequenceConfig& config) {
  std::map<char, sequence::TrialBasis> basis;
  for (const auto& t : config.trials) basis[t.robot] = readTrialBasis(t);
  return sequence::synchronizeTrials(config, basis);
}

std::unique_ptr<sequence::ScanSource> openTrialSource(const sequence::TrialConfig& trial) {
  std::unique_ptr<trials::TrialScanSource> scans = openTrialScanSource(trial);
  const bool caching = dynamic_cast<trials::CachingScanSource*>(scans.get()) != nullptr;  // complete the cache
  return std::make_unique<sequence::CoveredScanSource>(std::move(scans), trials::trialCoverage(trial), caching);
}

std::map<char, std::unique_ptr<sequence::ScanSource>> openTrialSources(const sequence::SequenceConfig& config) {
  std::map<char, std::unique_ptr<sequence::ScanSource>> sources;
  for (const auto& t : config.trials) sources[t.robot] = openTrialSource(t);
  return sources;
}

sequence::MergedScanStream openSequenceStream(const sequence::SequenceConfig& config,
                                              const sequence::SequenceTiming& timing) {
  return sequence::MergedScanStream(openTrialSources(config), timing);
}

}  // namespace cosmo::trials
