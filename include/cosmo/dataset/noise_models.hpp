#pragma once
// Noise models of a dataset (spec section 6): one constant 6x6 covariance for every odometry factor and one
// for every loop closure (intra- and inter-robot share it), in GTSAM's tangent order [rx, ry, rz, tx, ty, tz]
// (rotation first, rad^2 then m^2). They are estimated per environment by cosmo_noise_models and read from
// config/noise_models/<environment>.yaml.
//
// YAML layout (what save() writes and fromConfig() reads):
//   environment: tuhh                  # free text, informative
//   odometry:
//     covariance:                      # 6 rows of 6 numbers (or one flat list of 36), row by row
//       - [rx_rx, rx_ry, ..., rx_tz]
//       ...
//   loop_closure:
//     covariance: ...
// Instead of `covariance`, `sigmas: [s_rx, s_ry, s_rz, s_tx, s_ty, s_tz]` gives a diagonal model.
// Both sections are required. Optional keys say where the values come from (written into the dataset's
// metadata):
//   provenance: "..."                  # free text: where the numbers come from
//   estimated_from:                    # written by the estimation (cosmo_noise_models, cosmo_generate
//     trial: ...                       #   --estimate-noise-models): the run, the counts used, the thresholds
//     odometry_factors: 238
//     loop_closures: 119
//     loop_closures_left_out: 3
//     max_translation_error: 0.5
//     max_rotation_error: 0.05
// An environment whose models are not known has a file with `unknown: "<why>"` and no sections: loading it
// throws NoiseModelsUnknown, so that no run uses made-up values.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include "cosmo/common/config.hpp"
#include "cosmo/common/pose.hpp"

namespace cosmo::dataset {

/// What an estimated model was computed from (the YAML's `estimated_from`).
struct NoiseModelRecord {
  std::string trial;                       ///< the run: trial name, or the JRL it was read from
  std::size_t odometry_factors = 0;        ///< odometry measurements used
  std::size_t loop_closures = 0;           ///< good loop closures used
  std::size_t loop_closures_left_out = 0;  ///< loop closures over the thresholds
  double max_translation_error = 0.5;      ///< m, the "good" threshold
  double max_rotation_error = 0.05;        ///< rad
};

/// Thrown when a noise-model file says that its environment's models are unknown (`unknown: why`).
struct NoiseModelsUnknown : std::runtime_error {
  NoiseModelsUnknown(const std::string& what, std::string reason_)
      : std::runtime_error(what), reason(std::move(reason_)) {}
  std::string reason;
};

struct NoiseModels {
  Matrix6 odometry = defaultOdometry();            ///< covariance of BetweenFactorPose3 <r>(i-1) -> <r>i
  Matrix6 loop_closure = defaultLoopClosure();     ///< covariance of every loop closure (intra and inter)
  std::string environment = "synthetic";           ///< informative label written to / read from the YAML
  std::string provenance;                          ///< where the values come from (YAML `provenance`)
  std::optional<NoiseModelRecord> estimated_from;  ///< how they were estimated (YAML `estimated_from`)
  std::string source;  ///< the file they were loaded from (not written; "" when built in code)

  /// Read a config node (the root of a config/noise_models/*.yaml). Both sections are required; a missing or
  /// malformed one (wrong count, not symmetric, not positive definite, NaN) throws naming file and key; a file
  /// with `unknown:` throws NoiseModelsUnknown.
  static NoiseModels fromConfig(const ConfigNode& config);
  /// ConfigNode::load(path) + fromConfig.
  static NoiseModels load(const std::string& yaml_path);
  /// Write the YAML atomically (temp file + rename), doubles in shortest round-trip spelling, so that
  /// load(save(x)) == x bit for bit. `header_comment` lines are written as "# ..." at the top.
  void save(const std::string& yaml_path, const std::string& header_comment = "") const;
  /// The YAML text save() writes.
  std::string toYaml(const std::string& header_comment = "") const;
  /// One line for metadata and logs: "<file> (<environment>: <provenance>; estimated from <trial>: counts)".
  std::string describe() const;

  /// Values of a NoiseModels built in code (tests, benchmarks): the covariances stored in the reference
  /// COSMO-Bench file tuhh_r3_01_night_wifi.jrl (= config/noise_models/tuhh.yaml). The drivers never use them:
  /// a run loads the file its sequence names.
  static Matrix6 defaultOdometry();
  static Matrix6 defaultLoopClosure();
};

/// Throws std::runtime_error("<what>: ...") unless `cov` is finite, symmetric (relative 1e-9) and positive
/// definite.
void checkCovariance(const Matrix6& cov, const std::string& what);

}  // namespace cosmo::dataset
