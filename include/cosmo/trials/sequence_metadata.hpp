#pragma once
// The sequence's own lines of a dataset's metadata (`<name>_<comm>.recorder.yaml`, DatasetRecorder::setMetadata):
// the sequence's name and source, the one reference offset subtracted from every trial's reference positions,
// the sequence's own `registration:` keys when it has any, each robot's trial with its stamp convention, and
// `dewarp_<robot>: off` for a trial whose clouds carry no per-point time (trialDewarpOff; no line where its bag
// cannot be read, e.g. on another host). The offline driver and the recorder node write the same lines.
#include <string>
#include <utility>
#include <vector>

#include "cosmo/sequence/sequence_config.hpp"

namespace cosmo::trials {

/// `key: value` pairs (values as YAML text). Reads the anchor's reference when the offset is `anchor`; throws
/// naming the file when it cannot.
std::vector<std::pair<std::string, std::string>> sequenceMetadata(const sequence::SequenceConfig& config);

}  // namespace cosmo::trials
