#pragma once
// The per-transfer log a user can plot, and a back-end can model delay with: CSV with header
//   sender,receiver,keyframe,start,end,bytes,outcome,received,bytes_sent,link
// one row per transfer in the order they ended: start = radio time (s) of the step that began it, end = the step
// in which its last byte was sent (or it timed out), bytes = payload size, outcome delivered | timed_out,
// received = the step in which the receiver got the scan (end plus a trace's latency; empty when timed out),
// bytes_sent = bytes that got through, link = distance | trace | mixed (which link model decided its steps).
// Radio time is seconds since the summary's time_origin_ns (a UNIX stamp in ns; 0: radio time is UNIX time).
// And a JSON summary of the counters and parameters (with a trace: its file, windows, and how many connectivity
// samples it answered and how many fell back to phi(d)).
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "cosmo/comm/radio_simulator.hpp"

namespace cosmo::comm {

void writeTransferCsv(std::ostream& out, const std::vector<Transfer>& transfers);
/// Summary counters and the parameters as a JSON object.
nlohmann::json transferSummary(const RadioStats& stats, const RadioParams& params);
/// The same, with the radio's time origin and its trace's figures.
nlohmann::json transferSummary(const RadioSimulator& radio);
/// transferSummary() as one line of JSON.
std::string transferSummaryJson(const RadioStats& stats, const RadioParams& params);
/// Writes `csv_path` and `<csv_path without .csv>.summary.json`, each atomically (temp file, then rename).
/// Throws std::runtime_error naming the file on failure.
void writeTransferLog(const std::string& csv_path, const std::vector<Transfer>& transfers, const RadioStats& stats,
                      const RadioParams& params);
/// The radio's whole log (transferSummary(radio) as the summary), and its connectivity (comm/connectivity.hpp) as
/// connectivityPath(csv_path), e.g. `<dataset>_transfers.csv` -> `<dataset>_connectivity.json`.
void writeTransferLog(const std::string& csv_path, const RadioSimulator& radio);

}  // namespace cosmo::comm
