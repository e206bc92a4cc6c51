#pragma once
// cosmo_generate's options as a struct: what pipeline::generate (generate.hpp) runs. The command line and the
// request convert both ways here, side by side: addGenerateOptions / generateRequestFromArgs read one,
// generateArgs writes it; the suite builds requests and runs each as a cosmo_generate process.
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/noise_model_estimation.hpp"

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
  dataset::NoiseModelEstimationParams estimation;
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
/// The command line (without the program) that gives `request`: what the suite runs. Options at their defaults
/// are left out; numbers are written so that they read back as the same double.
std::vector<std::string> generateArgs(const GenerateRequest& request);
/// The request a command line (without the program) gives; throws std::runtime_error naming the option.
GenerateRequest generateRequestFromArgs(const std::vector<std::string>& args);

}  // namespace cosmo::pipeline
