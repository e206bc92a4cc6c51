#pragma once
// What a run of a sequence plays, resolved in one place for every driver (the player, cosmo_generate, cosmo_check,
// the suite's planner): the config (a file, or the built-in synthetic sequence, generated first), its seed and gate
// threshold as overridden, the noise models it labels with (sequence_noise_models.hpp), the pre-flight check
// (trial_probe.hpp), and from the trials' bases (their spans and references, however they are read) the time
// synchronization, the references and the end of the run.
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/sequence/sequence_timing.hpp"
#include "cosmo/sequence/trial_basis.hpp"

namespace cosmo::trials {

/// Which sequence a run plays and how (the drivers' options).
struct SequenceChoice {
  std::string sequence;         ///< config path; empty: the built-in synthetic sequence
  std::string data_root;        ///< empty: the config's precedence
  std::string simulate_config;  ///< the built-in sequence's generation config (empty: config/sim/default.yaml)
  std::string simulate_out = "/tmp/cosmo_builtin_sequence";
  std::string config_dir;      ///< where noise_models/<environment>.yaml is looked up (empty: the source tree's)
  std::string noise_models;    ///< a noise-model file overriding the sequence's
  std::string estimate_trial;  ///< the noise models are estimated first from this trial run alone (none loaded)
  std::optional<unsigned long long> seed;
  std::optional<double> gate_threshold;  ///< the registration gate's threshold (sequence/gate_threshold.hpp)
  double max_seconds = 0.0;              ///< 0: the whole sequence
  bool check = true;  ///< the pre-flight check before the trials are read (off where the trials are elsewhere)
};

/// The pre-flight check failed: report() holds its lines and verdict.
struct PreflightFailed : std::runtime_error {
  explicit PreflightFailed(std::string report_text)
      : std::runtime_error("the pre-flight check failed"), report(std::move(report_text)) {}
  std::string report;
};

/// Where a driver's log lines go (the built-in sequence's generation takes minutes: said before it starts).
using Say = std::function<void(const std::string&)>;

/// The config the choice names with its overrides (seed, gate threshold: std::invalid_argument outside its range);
/// the built-in sequence is generated first (once: cached).
sequence::SequenceConfig loadSequence(const SequenceChoice& choice, const Say& say = {});

/// The noise-model file a run of `config` reads, as the pre-flight check names it ("" when there is none; how
/// they are made when they are estimated first).
std::string noiseModelsSource(const SequenceChoice& choice, const sequence::SequenceConfig& config);

/// What the timing and references take from each trial, however the trials are read.
using TrialBases = std::function<std::map<char, sequence::TrialBasis>(const sequence::SequenceConfig&)>;

/// Each trial's basis read from its bag and reference (this machine has the trials).
std::map<char, sequence::TrialBasis> readTrialBases(const sequence::SequenceConfig& config);

struct ResolvedSequence {
  sequence::SequenceConfig config;
  std::string noise_source;                   ///< noiseModelsSource()
  std::optional<dataset::NoiseModels> noise;  ///< none while they are to be estimated (SequenceChoice::estimate_trial)
  std::string check_report;                   ///< the pre-flight check's lines (empty when it was not run)
  sequence::SequenceTiming timing;
  std::map<char, Trajectory> references;  ///< robot -> sensor trajectory in the world frame, sequence time
  StampNs end = 0;                        ///< the sequence end, or max_seconds after its start

  std::vector<char> robots() const;
  double seconds() const { return toSeconds(end - timing.start()); }
};

/// Loads the config, its noise models (throws sequence::NoiseModelsMissing with the how-to), runs the pre-flight
/// check (throws PreflightFailed), then takes the trials' bases from `bases` and resolves the rest from them.
/// `say` receives the built-in sequence's command and, once per trial, that its sweeps are not dewarped
/// (trialDewarpOff; not said of a trial whose bag is not on this machine, as at a base whose robots play).
ResolvedSequence resolveSequence(const SequenceChoice& choice, const TrialBases& bases = readTrialBases,
                                 const Say& say = {});

}  // namespace cosmo::trials
