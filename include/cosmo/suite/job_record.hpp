#pragma once
// The record of a finished job, `<job folder>/suite.json`, and one line of `<out>/manifest.jsonl`: what it read
// (each input's identity), with which parameters and program, what it wrote (each output's size and SHA-256),
// the datasets' figures (paper Fig. 1 statistics, validation, the inlier solve), and its cost. A job's outputs
// are current when its folder holds a record whose inputs and parameters are the plan's and whose outputs are
// unchanged; otherwise the record says why not.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

struct OutputFile {
  std::string file;  ///< relative to the job's folder
  std::uintmax_t size = 0;
  std::string sha256;
};

/// One dataset of a group, as the report shows it.
struct DatasetSummary {
  std::string name, comm, jrl;  ///< jrl, figure: file names in the job's folder
  std::string figure;           ///< the trajectories figure (.svg), "" when none
  double duration_s = 0.0, length_m = 0.0;
  std::size_t lc = 0, lc_outliers = 0, irlc = 0, irlc_outliers = 0;
  bool labelled = false;
  std::size_t violations = 0;
  double inliers_ate_m = -1.0, init_ate_m = -1.0;  ///< -1: no solve (solve_note says why)
  std::string solve_note;
};

struct JobRecord {
  std::string job, kind, key, run_id, finished;  ///< finished: UTC, ISO 8601
  std::vector<std::string> command;              ///< the program's command line as run
  std::map<std::string, std::string> inputs;     ///< "<what> <path>" -> identity
  std::vector<OutputFile> outputs;
  std::vector<DatasetSummary> datasets;
  double wall_s = 0.0, cpu_s = 0.0, peak_rss_mb = 0.0, sequence_seconds = 0.0;
  unsigned registration_threads = 0;

  std::string toJson() const;  ///< one line
  static JobRecord fromJson(const std::string& text, const std::string& where);
};

/// Input identities, each file read once per process (programs are large).
class IdentityCache {
 public:
  std::string get(const InputFile& in);

 private:
  std::map<std::string, std::string> known_;
};

/// "<what> <path>" -> identity of every input of `job`.
std::map<std::string, std::string> inputIdentities(const Job& job, IdentityCache& cache);

/// The hash of what decides a job's outputs: its kind, arguments, config keys, post-steps and input identities.
std::string jobKey(const Job& job, const std::map<std::string, std::string>& identities);

/// The name of a job's record in its folder.
inline constexpr const char* kRecordFile = "suite.json";

struct JobState {
  enum class Kind { Current, Missing, Stale };
  Kind kind = Kind::Missing;
  std::string reason;  ///< Stale / Missing: why, e.g. "sequence changed: /x/seq.yaml"
};

/// Whether the job's folder holds its current outputs (see the file comment).
JobState checkJob(const Plan& plan, const Job& job, IdentityCache& cache);

/// Reads `<folder>/suite.json`; false when there is none or it does not parse.
bool readRecord(const std::string& folder, JobRecord& record);

}  // namespace cosmo::suite
