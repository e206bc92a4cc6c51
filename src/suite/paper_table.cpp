#include "cosmo/suite/paper_table.hpp"

#include <stdexcept>

#include "cosmo/common/config.hpp"

namespace cosmo::suite {

double parseMinutesSeconds(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 3 != text.size())
    throw std::invalid_argument("expected MM:SS, got '" + text + "'");
  return 60.0 * std::stod(text.substr(0, colon)) + std::stod(text.substr(colon + 1));
}

PaperTable PaperTable::load(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  root.rejectUnknownKeys({"sequences"});
  PaperTable table;
  int i = 0;
  for (const auto& item : root.node["sequences"]) {
    const ConfigNode n{item, root["sequences"].where + "[" + std::to_string(i++) + "]"};
    n.rejectUnknownKeys({"name", "source", "trials", "duration", "length_km", "lc", "lc_pct", "irlc_wifi",
                         "irlc_wifi_pct", "irlc_proradio", "irlc_proradio_pct"});
    PaperRow r;
    std::string duration;
    double km = 0.0;
    n.read("name", r.name);
    n.read("source", r.source);
    n.read("trials", r.trials);
    n.read("duration", duration);
    n.read("length_km", km);
    n.read("lc", r.lc);
    n.read("lc_pct", r.lc_pct);
    for (const char* comm : {"wifi", "proradio"}) {
      std::pair<std::size_t, double> v;
      n.read(std::string("irlc_") + comm, v.first);
      n.read(std::string("irlc_") + comm + "_pct", v.second);
      r.irlc[comm] = v;
    }
    try {
      r.duration_s = parseMinutesSeconds(duration);
    } catch (const std::invalid_argument& e) { throw std::runtime_error(n.where + ".duration: " + e.what()); }
    r.length_m = 1000.0 * km;
    if (r.name.empty()) throw std::runtime_error(n.where + ".name: missing");
    table.rows_[r.name] = r;
  }
  return table;
}

std::optional<PaperRow> PaperTable::find(const std::string& sequence_name) const {
  const auto it = rows_.find(sequence_name);
  if (it == rows_.end()) return std::nullopt;
  return it->second;
}

}  // namespace cosmo::suite
