#pragma once
// The offline driver's policy, of which cosmo_generate is the command line: a GenerateRequest (the options as a
// struct; addGenerateOptions reads it from a command line, generateArgs writes it back, side by side, for the
// suite, which runs each job as a process) -> the sequence resolved (trials::resolveSequence) -> its noise models
// (the sequence's, or estimated first from one trial run alone) -> per comm model a TeamRun fed (feed.hpp) and its
// dataset written: <out>/<name>_<comm>.jrl (+ .recorder.yaml, .stats.txt) and <out>/<name>_<comm>_transfers.csv
// (+ .summary.json). Deterministic: the same request gives the same bytes, whatever the threads.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/pipeline/feed.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/trials/sequence_resolution.hpp"

namespace cosmo::pipeline {

struct GenerateRequest {
  std::string sequence, data_root;       ///< the sequence config and the data root it is read against
  std::vector<std::string> comms{"wifi"};  ///< comm models (comm/comm_model.hpp), one dataset each
  std::optional<unsigned long long> seed;  ///< overrides the sequence's
  std::string out_dir = ".";
  std::string config_dir;                 ///< frontend/odometry/.../comm/noise_models configs (empty: the source tree's)
  std::string noise_models;               ///< a noise-model file overriding the sequence's
  std::string outlier_rule = "fidelity";  ///< fidelity or squared
  std::string estimate_trial;    ///< estimate the noise models first from this trial run alone
  std::string noise_models_out;  ///< where the estimate goes (empty: beside the outputs)
  bool estimate_only = false;    ///< write the estimate and stop
  NoiseModelEstimationParams estimation;
  std::string odometry = "loam";  ///< loam or reference (FrontendParams::odometry)
  bool serial_odometry = false;   ///< every robot's work on the team's thread
  std::optional<unsigned> registration_threads;  ///< none: the machine's cores (0 with serial odometry)
  double max_seconds = 0.0;                      ///< 0: the whole sequence
  std::optional<double> gate_threshold;          ///< the registration gate's threshold (sequence/gate_threshold.hpp)
  bool check = true;                             ///< the pre-flight check first
  bool quiet = false;                            ///< less output (the tool's)

  /// Options that need each other or a range; throws std::runtime_error naming the option.
  void validate() const;
};

/// Declares cosmo_generate's command line on `app`, read into `request` (the sequence is the positional argument).
void addGenerateOptions(CLI::App& app, GenerateRequest& request);
/// The command line (without the program) that gives `request`: what the suite runs.
std::vector<std::string> generateArgs(const GenerateRequest& request);

/// One comm model's dataset.
struct GeneratedDataset {
  std::string label;          ///< the comm model's (comm/comm_model.hpp)
  std::string jrl, transfers;  ///< the files written
  BuildReport report;
  FeedFigures feed;
};

/// What a person sees of a run, told as it happens (all optional).
struct GenerateLog {
  std::function<void(const std::string&)> preflight;  ///< the pre-flight check's report (it passed)
  std::function<void(const trials::ResolvedSequence&)> resolved;  ///< the sequence, resolved
  std::function<void(const std::string&)> line;  ///< the sequence's summary, the estimate (lines end with '\n')
  std::function<void(const std::string& label)> run_starts;  ///< a comm model's run starts
  std::function<void(const TeamRun&, StampNs stamp)> progress;  ///< after each scan fed (progress lines)
  /// A dataset was written; `run` holds its team (summaries, figures).
  std::function<void(const TeamRun& run, const GeneratedDataset& dataset)> written;
  /// The wall clock for FeedFigures (the core reads none).
  std::function<double()> wall_clock;
};

struct GenerateResult {
  trials::ResolvedSequence sequence;
  NoiseModels noise;
  std::vector<GeneratedDataset> datasets;  ///< none with estimate_only
};

/// Runs the request. Throws std::runtime_error with the reason (a failed pre-flight check: its report first, on
/// log.line).
GenerateResult generate(const GenerateRequest& request, const GenerateLog& log = {});

}  // namespace cosmo::pipeline
