#include "cosmo/trials/sequence_metadata.hpp"

#include <cstdio>
#include <string>

#include "cosmo/trials/bag_scan_source.hpp"
#include "cosmo/trials/trial_reference.hpp"

namespace cosmo::trials {

std::vector<std::pair<std::string, std::string>> sequenceMetadata(const sequence::SequenceConfig& config) {
  const Eigen::Vector3d o = sequenceReferenceOffset(config);
  char offset[160];
  std::snprintf(offset, sizeof offset, "[%.3f, %.3f, %.3f]  # m, subtracted from every reference position", o.x(),
                o.y(), o.z());
  std::vector<std::pair<std::string, std::string>> lines{
      {"sequence", config.name}, {"source", config.source}, {"reference_offset", offset}};
  if (!config.registration.empty()) {
    std::string keys;
    for (const auto& [key, value] : config.registration) keys += (keys.empty() ? "" : ", ") + key + ": " + value;
    lines.push_back({"registration", "{" + keys + "}  # the sequence's own keys over config/registration.yaml"});
  }
  for (const auto& t : config.trials)
    lines.push_back({std::string("trial_") + t.robot, t.name + "  # stamp " + (t.stamp_at_end ? "end" : "start")});
  for (const auto& t : config.trials) {
    std::string off;
    try {
      off = trialDewarpOff(t);
    } catch (const std::exception&) {}  // its bag cannot be read where the metadata is written: no line
    if (!off.empty()) lines.push_back({std::string("dewarp_") + t.robot, "off  # " + off});
  }
  return lines;
}

}  // namespace cosmo::trials
