#pragma once
// The trials of a sequence config read from their bags, whatever the container (the pipeline's drivers, the
// `player` node, `cosmo_generate`, pre-flight checks): a trial's `bag:` may name a ROS 1 bag, a ROS 2 sqlite3
// bag folder or its .db3, told apart by content (trials::detectBagFormat); both are read by the ROS-free trials
// module (trials::Ros1ScanSource, trials::Ros2ScanSource). Errors throw std::runtime_error naming the bag and topic.
#include <map>
#include <memory>
#include <string>

#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/sequence/trial_basis.hpp"
#include "cosmo/trials/trial_scans.hpp"

namespace cosmo::trials {

/// The scans of one trial (its bag, topic and stamp convention), from a ROS 1 or ROS 2 bag. A ROS 1 bag with
/// compressed chunks is read through the scan cache (trials/scan_cache.hpp; COSMO_SCAN_CACHE=off disables it):
/// the first complete read decodes it and fills the cache, later ones read bit-identical scans from it.
std::unique_ptr<trials::TrialScanSource> openTrialScanSource(const sequence::TrialConfig& trial);

/// Header stamps of the trial's first and last PointCloud2 (reads only the first message and the messages of
/// the bag's last few seconds), from a ROS 1 or ROS 2 bag. Read once per process and bag; a ROS 1 bag with
/// compressed chunks keeps them beside its scan cache (trials::scanSpanPath), so later runs read none of the bag.
sequence::TrialSpan readTrialSpan(const sequence::TrialConfig& trial);

/// readTrialSpan as stamps of the sweep ends (the stamps of the decoded scans, whatever the trial's convention).
sequence::TrialSpan readSweepEndSpan(const sequence::TrialConfig& trial);

/// What the sequence's timing and references take from a trial (sequence/trial_basis.hpp): its sweep-end span
/// clipped to its reference's span (sequence/trial_coverage.hpp) and its reference as read.
sequence::TrialBasis readTrialBasis(const sequence::TrialConfig& trial);

/// Whether the trial's sweeps are dewarped: "" when its clouds carry per-point times (the decoder's conventions,
/// trials::pointConventions, decide which do), else why not, e.g. "its clouds carry no per-point time (fields
/// x:float32@0 y:float32@4 z:float32@8): its sweeps are not dewarped". Reads the trial's first message.
std::string trialDewarpOff(const sequence::TrialConfig& trial);

/// The synchronized timing of a sequence config (reads every trial's basis).
sequence::SequenceTiming synchronizeSequence(const sequence::SequenceConfig& config);

/// A reader of the trial's scans in recorded time: only the scans its reference covers
/// (sequence::CoveredScanSource).
std::unique_ptr<sequence::ScanSource> openTrialSource(const sequence::TrialConfig& trial);

/// openTrialSource for each trial (robot -> source).
std::map<char, std::unique_ptr<sequence::ScanSource>> openTrialSources(const sequence::SequenceConfig& config);

/// One merged stream over all trials of a sequence config, in sequence time.
sequence::MergedScanStream openSequenceStream(const sequence::SequenceConfig& config,
                                              const sequence::SequenceTiming& timing);

}  // namespace cosmo::trials
