#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/comm/radio_trace.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace cosmo::comm {

void writeTransferCsv(std::ostream& out, const std::vector<Transfer>& transfers) {
  out << "sender,receiver,keyframe,start,end,bytes,outcome,received,bytes_sent,link\n";
  out << std::fixed << std::setprecision(3);
  for (const Transfer& x : transfers) {
    out << x.sender << ',' << x.receiver << ',' << x.keyframe << ',' << x.start << ',' << x.end << ',' << x.bytes << ','
        << toString(x.outcome) << ',';
    if (std::isfinite(x.received)) out << x.received;
    out << ',' << static_cast<std::uint64_t>(std::floor(x.bytes_delivered)) << ',' << toString(x.link) << '\n';
  }
}

nlohmann::json transferSummary(const RadioStats& s, const RadioParams& p) {
  nlohmann::json j;
  j["steps"] = s.steps;
  j["keyframes_offered"] = s.keyframes_offered;
  j["init_attempts"] = s.init_attempts;
  j["initiated"] = s.initiated;
  j["delivered"] = s.delivered;
  j["timed_out"] = s.timed_out;
  j["link_samples"] = s.link_samples;
  j["link_successes"] = s.link_successes;
  j["bytes_delivered"] = s.bytes_delivered;
  j["bytes_transmitted"] = s.bytes_transmitted;
  j["params"] = {{"bandwidth_kBps", p.bandwidth_kBps},
                 {"d_init", p.d_init},
                 {"d_intf", p.d_intf},
                 {"p_max", p.p_max},
                 {"alpha", p.alpha},
                 {"beta", p.beta},
                 {"r_max", p.r_max},
                 {"step", p.step},
                 {"timeout", p.timeout},
                 {"timeout_mode", toString(p.timeout_mode)},
                 {"size_model", toString(p.size_model)}};
  return j;
}

nlohmann::json transferSummary(const RadioSimulator& radio) {
  nlohmann::json j = transferSummary(radio.stats(), radio.params());
  j["time_origin_ns"] = radio.timeOrigin();
  j["in_flight"] = radio.stats().in_flight;
  if (const auto& trace = radio.params().trace)
    j["trace"] = {{"file", trace->source()},
                  {"windows", trace->windowCount()},
                  {"samples_from_trace", radio.stats().trace_samples},
                  {"samples_from_distance_model", radio.stats().fallback_samples}};
  return j;
}

std::string transferSummaryJson(const RadioStats& s, const RadioParams& p) { return transferSummary(s, p).dump(); }

namespace {
void writeAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(path + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot rename temporary file: " + ec.message());
}

void writeLogFiles(const std::string& csv_path, const std::vector<Transfer>& transfers, const nlohmann::json& summary) {
  std::ostringstream csv;
  writeTransferCsv(csv, transfers);
  writeAtomically(csv_path, csv.str());
  std::string base = csv_path;
  if (base.size() > 4 && base.compare(base.size() - 4, 4, ".csv") == 0) base.resize(base.size() - 4);
  writeAtomically(base + ".summary.json", summary.dump() + "\n");
}
}  // namespace

void writeTransferLog(const std::string& csv_path, const std::vector<Transfer>& transfers, const RadioStats& stats,
                      const RadioParams& params) {
  writeLogFiles(csv_path, transfers, transferSummary(stats, params));
}

void writeTransferLog(const std::string& csv_path, const RadioSimulator& radio) {
  writeLogFiles(csv_path, radio.transferLog(), transferSummary(radio));
  writeAtomically(connectivityPath(csv_path), radio.connectivity().toJson().dump() + "\n");
}

}  // namespace cosmo::comm
