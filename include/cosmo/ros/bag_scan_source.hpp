#pragma once
// The trials of a sequence config read from their bags (ROS glue for the pipeline's drivers, the `player`
// node and `cosmo_generate`): each trial's first/last scan stamps (for the synchronization) and a
// pipeline::ScanSource over its scans. Errors throw std::runtime_error naming the bag and topic.
#include <map>
#include <memory>
#include <string>

#include "cosmo/pipeline/scan_stream.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_timing.hpp"
#include "cosmo/ros/bag_io.hpp"

namespace cosmo::ros_glue {

/// Sweep-end stamps of the first and the last PointCloud2 message on `topic` (reads only the first message and
/// the messages of the bag's last few seconds; a start-stamped trial's scans are decoded for their latest point).
pipeline::TrialSpan readTrialSpan(const std::string& bag_path, const std::string& topic, char robot,
                                  bool stamp_at_end = true);

/// ScanBagReader as a pipeline::ScanSource.
class BagScanSource : public pipeline::ScanSource {
 public:
  BagScanSource(const std::string& bag_path, const std::string& topic, bool stamp_at_end = true)
      : reader_(bag_path, topic, stamp_at_end) {}
  bool next(Scan& scan) override { return reader_.next(scan); }
  std::size_t size() const { return reader_.size(); }

 private:
  ScanBagReader reader_;
};

/// The synchronized timing of a sequence config (reads every trial's span, clipped to its reference's span:
/// pipeline/trial_coverage.hpp).
pipeline::SequenceTiming synchronizeSequence(const pipeline::SequenceConfig& config);

/// A reader of each trial's scans (robot -> source), in recorded time: stamped at the sweep end, only the scans
/// its reference covers (pipeline::CoveredScanSource).
std::map<char, std::unique_ptr<pipeline::ScanSource>> openTrialSources(const pipeline::SequenceConfig& config);

/// One merged stream over all trials of a sequence config, in sequence time.
pipeline::MergedScanStream openSequenceStream(const pipeline::SequenceConfig& config,
                                              const pipeline::SequenceTiming& timing);

}  // namespace cosmo::ros_glue
