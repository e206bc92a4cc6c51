#pragma once
// The radio's state as it is shown while it runs (the comm_broker's /comm/stats and link markers): the summary
// counters, the active transfers and what waits per link, and a link's mean throughput so far.
#include <map>
#include <utility>

#include <nlohmann/json.hpp>

#include "cosmo/comm/radio_simulator.hpp"

namespace cosmo::comm {

/// transferSummary() at radio time `t` (s), with the active transfers ("active") and the undelivered keyframes
/// per ordered pair of robots ("pending", keys "a->b").
nlohmann::json radioStatus(const RadioSimulator& radio, double t);

/// A link's mean throughput since its transfer started, as a fraction of the bandwidth, at radio time `t` (s) of
/// its latest step (the steps so far times delta).
double linkThroughputFraction(const ActiveCommunication& link, double t, const RadioParams& params);

/// The links of the latest step, one per (sender, receiver).
std::map<std::pair<char, char>, ActiveCommunication> lastStepLinks(const RadioSimulator& radio);

}  // namespace cosmo::comm
