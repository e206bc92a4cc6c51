#pragma once
// The registration gate's acceptance threshold as one number a sweep can vary (a suite variant): the strict gate's
// `min_structure_overlap` (registration/registration_gate.hpp), the share of the source's structure points (walls,
// poles: |normal z| < 0.9) that lie within 0.9 m of the target after the solve. It is the test that separates right
// from wrong registrations (config/registration.yaml: wrong solutions and non-overlapping pairs measured up to 0.58,
// right ones from 0.64; default 0.62), so moving it moves the share of genuine front-end outliers in a dataset:
// lower accepts more wrong alignments, higher rejects more right ones. Meaningful sweep 0.40-0.70; 0 switches the
// test off (the other checks of the strict gate stay).
#include <map>
#include <string>

#include "cosmo/sequence/sequence_config.hpp"

namespace cosmo::sequence {

constexpr double kGateThresholdMin = 0.0, kGateThresholdMax = 1.0;

/// The sequence's `registration:` keys for a gate threshold: `gate: strict`, `min_structure_overlap: <threshold>`
/// (on top of the sequence's own keys). Throws std::invalid_argument outside [0, 1].
std::map<std::string, std::string> gateThresholdKeys(double threshold);
/// The same applied to `config` (its other registration keys kept, e.g. `refine: false`).
void applyGateThreshold(SequenceConfig& config, double threshold);

}  // namespace cosmo::sequence
