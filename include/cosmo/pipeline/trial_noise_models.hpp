#pragma once
// The paper's noise-model step (spec section 6) for one environment: run one designated trial alone through
// the front-end (LOAM odometry, keyframes, its own loop closures; no team, no radio traffic), compare its
// odometry and loop closures with the reference solution, keep the good loop closures (under the thresholds)
// and take the sample covariances (estimateNoiseModels, noise_model_estimation.hpp). cosmo_generate
// --estimate-noise-models runs it before a sequence; cosmo_noise_models does the comparison on a JRL.
#include <map>
#include <string>

#include "cosmo/common/trajectory.hpp"
#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/sequence/scan_stream.hpp"
#include "cosmo/pipeline/team_run.hpp"

namespace cosmo::pipeline {

struct TrialNoiseModels {
  dataset::NoiseModelEstimate estimate;  ///< models (with environment, provenance and estimated_from filled) and counts
  jrl::Dataset run;                      ///< the single-trial run (its outlier labels are meaningless: no models yet)
};

/// Runs `stream` (one robot's scans, sequence time) through a TeamRun of that robot alone with `params`
/// (params.noise is not used for anything kept), then estimates the models from its measurements against
/// `reference` (the robot's sensor trajectory, sequence time). `trial_label` and `environment` are written
/// into the result. Throws std::runtime_error when the run has too few measurements (names the counts).
TrialNoiseModels estimateTrialNoiseModels(char robot, sequence::MergedScanStream& stream, const Trajectory& reference,
                                          const TeamRunParams& params, std::uint64_t radio_seed,
                                          const dataset::NoiseModelEstimationParams& estimation,
                                          const std::string& trial_label, const std::string& environment);

}  // namespace cosmo::pipeline
