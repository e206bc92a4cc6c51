#pragma once
// The paper's Fig. 1 values of its 12 sequences (config/paper/fig1.yaml, which names its source), for the
// report's "ours beside the paper's" columns.
#include <map>
#include <optional>
#include <string>

namespace cosmo::suite {

struct PaperRow {
  std::string name, source, trials;
  double duration_s = 0.0, length_m = 0.0;
  std::size_t lc = 0;
  double lc_pct = 0.0;
  std::map<std::string, std::pair<std::size_t, double>> irlc;  ///< comm model -> (count, outlier %)
};

class PaperTable {
 public:
  /// Reads the table; throws std::runtime_error naming the file and the entry.
  static PaperTable load(const std::string& path);
  /// The row of a sequence name, if the paper has one.
  std::optional<PaperRow> find(const std::string& sequence_name) const;
  std::size_t size() const { return rows_.size(); }

 private:
  std::map<std::string, PaperRow> rows_;
};

/// "MM:SS" -> seconds; throws std::invalid_argument otherwise.
double parseMinutesSeconds(const std::string& text);

}  // namespace cosmo::suite
