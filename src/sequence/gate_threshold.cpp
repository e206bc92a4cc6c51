#include "cosmo/sequence/gate_threshold.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cosmo::sequence {

std::map<std::string, std::string> gateThresholdKeys(double threshold) {
  if (!std::isfinite(threshold) || threshold < kGateThresholdMin || threshold > kGateThresholdMax)
    throw std::invalid_argument("gate threshold (min_structure_overlap) must be in [0, 1], got " +
                                std::to_string(threshold));
  std::ostringstream value;
  value.precision(15);  // as a person writes it: 0.58, not 0.57999999999999996
  value << threshold;
  return {{"gate", "strict"}, {"min_structure_overlap", value.str()}};
}

void applyGateThreshold(SequenceConfig& config, double threshold) {
  for (const auto& [key, value] : gateThresholdKeys(threshold)) config.registration[key] = value;
}

}  // namespace cosmo::sequence
