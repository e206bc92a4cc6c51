#pragma once
// The jobs of a suite: one per noise-model estimate and one per sequence and variant (a dataset group: the
// datasets of its comm models, made by one cosmo_generate run that shares the odometry pass between them).
// Every job says the command it runs, the files it reads (their identity decides whether its outputs are
// current), and the jobs it waits for (a dataset group that uses an estimate waits for it).
//
// A group that reads a compressed ROS 1 bag (MCD: bz2) whose scan cache is still empty starts after the first group
// that reads it: the first pass decompresses it (libbz2, the slowest step of a run) and fills the cache the later
// ones read, instead of each decompressing it again side by side.
//
// Names: a group is <label>[_<variant part>...] (e.g. ci_mcd_s1), its datasets <group>_<comm> (ci_mcd_s1_wifi);
// an estimate is noise_models/<name>. Each job writes into its own folder below the output folder (<group>/,
// noise_models/<name>/).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cosmo/pipeline/generate_request.hpp"
#include "cosmo/suite/suite_file.hpp"

namespace cosmo::suite {

/// A file a job reads, and what it is for ("sequence", "bag a", "reference a", "config registration.yaml", ...).
struct InputFile {
  std::string what;
  std::string path;
  bool always_hash = false;  ///< programs: hashed whatever their size
};

struct Job {
  enum class Kind { Estimate, Datasets };
  Kind kind = Kind::Datasets;
  std::string id;             ///< group name, or "noise_models/<name>"
  std::string label;          ///< the sequence entry's label
  std::string sequence;       ///< the sequence config (absolute path)
  std::string sequence_name;  ///< its `name:`: cosmo_generate writes <sequence_name>_<comm>.*
  std::vector<std::string> comms;
  /// What its cosmo_generate runs, but the output folder and the registration threads (estimates: also where the
  /// estimate goes): run_job.cpp sets those and runs pipeline::generateArgs(request) as a process.
  pipeline::GenerateRequest request;
  std::map<std::string, std::string> registration, radio;  ///< config keys set by variants (a config copy)
  std::vector<PostStep> post_steps;
  std::vector<std::string> depends_on;  ///< job ids whose outputs it needs (a noise-model estimate)
  /// Job ids it starts after, done or not: the group that first decodes a compressed bag it also reads (its scan
  /// cache is empty), so that each bag is decompressed once (plan_inputs.hpp).
  std::vector<std::string> after;
  std::vector<InputFile> inputs;
  int robots = 1;        ///< threads of its odometry pass (one per robot)
  double seconds = 0.0;  ///< sequence time it processes (estimated from the references; for the ETA)

  /// "<id>_<comm>" per comm model (estimates: none).
  std::vector<std::string> datasetNames() const;
  /// The JRL cosmo_generate writes for `comm` (file name in the job's folder).
  std::string jrlFile(const std::string& comm) const { return sequence_name + "_" + comm + ".jrl"; }
  /// The file an estimate writes, relative to its folder: <name>.yaml.
  std::string estimateFile() const;
};

struct Plan {
  std::string suite_path, suite_name, out_dir, config_dir;  ///< config_dir: the one the jobs read (absolute)
  std::string program_dir;  ///< where cosmo_generate, cosmo_jrl and cosmo_suite are
  double max_seconds = 0.0;
  std::vector<Job> jobs;  ///< estimates first, then the groups in the suite file's order

  const Job& job(const std::string& id) const;  ///< throws naming the id when there is none
  std::string toJson() const;
  static Plan fromJson(const std::string& text, const std::string& where);
};

/// What planSuite needs besides the suite file.
struct PlanOptions {
  std::string out_dir;      ///< absolute
  std::string data_root;    ///< the command's --data-root ("" = each sequence's own rule)
  std::string program_dir;  ///< the folder of the cosmo programs
  std::string default_config_dir;
  /// The sequence config of a `simulate:` entry (runs cosmo_simulate); throws when it fails.
  std::function<std::string(const SequenceEntry&)> simulate;
};

/// Expands a suite into its jobs. Throws std::runtime_error naming the suite file (and the entry) for anything
/// that would fail later: a sequence that does not load, trial files that do not exist (all listed at once), two
/// groups with one name, an estimate whose `from` / `for` names no sequence (with the nearest label), a variant
/// setting a registration key its sequence sets itself.
Plan planSuite(const SuiteFile& suite, const PlanOptions& options);

/// The folder of a job's outputs, <out>/<id>.
std::string jobFolder(const Plan& plan, const Job& job);

}  // namespace cosmo::suite
