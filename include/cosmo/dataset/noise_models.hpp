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
#include <string>

#include "cosmo/common/config.hpp"
#include "cosmo/common/pose.hpp"

namespace cosmo {

struct NoiseModels {
  Matrix6 odometry = defaultOdometry();      ///< covariance of BetweenFactorPose3 <r>(i-1) -> <r>i
  Matrix6 loop_closure = defaultLoopClosure();  ///< covariance of every loop closure (intra and inter)
  std::string environment = "synthetic";     ///< informative label written to / read from the YAML

  /// Read a config node (the root of a config/noise_models/*.yaml). A missing section keeps the default;
  /// a malformed one (wrong count, not symmetric, not positive definite, NaN) throws naming file and key.
  static NoiseModels fromConfig(const ConfigNode& config);
  /// ConfigNode::load(path) + fromConfig.
  static NoiseModels load(const std::string& yaml_path);
  /// Write the YAML atomically (temp file + rename), doubles in shortest round-trip spelling, so that
  /// load(save(x)) == x bit for bit. `header_comment` lines are written as "# ..." at the top.
  void save(const std::string& yaml_path, const std::string& header_comment = "") const;
  /// The YAML text save() writes.
  std::string toYaml(const std::string& header_comment = "") const;

  /// Built-in defaults (= config/noise_models/synthetic.yaml): placeholders equal to the covariances stored
  /// in the reference COSMO-Bench file tuhh_r3_01_night_wifi.jrl, until a synthetic run re-estimates them.
  static Matrix6 defaultOdometry();
  static Matrix6 defaultLoopClosure();
};

/// Throws std::runtime_error("<what>: ...") unless `cov` is finite, symmetric (relative 1e-9) and positive
/// definite.
void checkCovariance(const Matrix6& cov, const std::string& what);

}  // namespace cosmo
