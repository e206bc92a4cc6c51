#include "cosmo/comm/radio_status.hpp"

#include <algorithm>
#include <string>

#include "cosmo/comm/transfer_log.hpp"

namespace cosmo::comm {

nlohmann::json radioStatus(const RadioSimulator& radio, double t) {
  nlohmann::json j = transferSummary(radio.stats(), radio.params());
  j["time"] = t;
  j["active"] = nlohmann::json::array();
  for (const auto& c : radio.activeCommunications())
    j["active"].push_back({{"sender", std::string(1, c.sender)},
                           {"receiver", std::string(1, c.receiver)},
                           {"keyframe", c.keyframe},
                           {"bytes", c.bytes},
                           {"progress", c.bytes ? c.bytes_delivered / static_cast<double>(c.bytes) : 1.0},
                           {"distance", c.distance},
                           {"interference", c.interference}});
  nlohmann::json pending = nlohmann::json::object();
  for (char a : radio.robots())
    for (char b : radio.robots())
      if (a != b) pending[std::string(1, a) + "->" + std::string(1, b)] = radio.undeliveredCount(a, b);
  j["pending"] = pending;
  return j;
}

double linkThroughputFraction(const ActiveCommunication& link, double t, const RadioParams& params) {
  const double duration = t - link.start + params.step;
  const double mean_rate = link.bytes_delivered / std::max(duration, params.step);
  return mean_rate / params.bandwidthBps();
}

std::map<std::pair<char, char>, ActiveCommunication> lastStepLinks(const RadioSimulator& radio) {
  std::map<std::pair<char, char>, ActiveCommunication> links;
  for (const auto& c : radio.lastStepCommunications()) links[{c.sender, c.receiver}] = c;
  return links;
}

}  // namespace cosmo::comm
