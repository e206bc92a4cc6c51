#pragma once
// The per-transfer log a user can plot: CSV with header sender,receiver,keyframe,start,end,bytes,outcome
// (times in s, bytes = payload size, outcome delivered | timed_out), and a JSON summary of the counters.
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "cosmo/comm/radio_simulator.hpp"

namespace cosmo {

void writeTransferCsv(std::ostream& out, const std::vector<Transfer>& transfers);
/// Summary counters and the parameters as a JSON object.
nlohmann::json transferSummary(const RadioStats& stats, const RadioParams& params);
/// transferSummary() as one line of JSON.
std::string transferSummaryJson(const RadioStats& stats, const RadioParams& params);
/// Writes `csv_path` and `<csv_path without .csv>.summary.json`, each atomically (temp file, then rename).
/// Throws std::runtime_error naming the file on failure.
void writeTransferLog(const std::string& csv_path, const std::vector<Transfer>& transfers, const RadioStats& stats,
                      const RadioParams& params);

}  // namespace cosmo
