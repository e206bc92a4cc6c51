#pragma once
// Empirical noise models (spec section 6): for measurements m of relative poses with reference values m*
// (from the reference solution), r = Log(m^-1 * m*) (rotation first) and Q = (1/N) sum r r^T (the paper's
// sum divided by the count: the second moment about zero, so a bias counts as error; subtract_mean gives
// the centred sample covariance instead). Loop closures enter only when "good": translation error
// |t(m^-1 m*)| < 0.5 m and rotation error angle(m^-1 m*) < 0.05 rad (configurable). Odometry is used whole.
#include <cstddef>
#include <optional>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::dataset {

/// A measured relative pose and its reference ("true") value, both T_1^-1 * T_2.
struct MeasurementWithTruth {
  Pose3 measurement = Pose3::Identity();
  Pose3 truth = Pose3::Identity();
};

struct NoiseModelEstimationParams {
  double max_translation_error = 0.5;  ///< m: loop closures with a larger error are not used
  double max_rotation_error = 0.05;    ///< rad: loop closures with a larger error are not used
  bool subtract_mean = false;          ///< true: centred sample covariance (divide by N-1)
  std::size_t min_samples = 10;        ///< fewer usable measurements: error (6 is the bare minimum)
};

/// What one covariance was computed from.
struct CovarianceEstimate {
  Matrix6 covariance = Matrix6::Identity();
  Vector6 mean_residual = Vector6::Zero();  ///< mean of r (a bias shows here)
  std::size_t used = 0;                     ///< measurements that entered Q
  std::size_t rejected = 0;                 ///< measurements over the thresholds (loop closures only)
};

struct NoiseModelEstimate {
  NoiseModels models;
  CovarianceEstimate odometry;
  CovarianceEstimate loop_closure;
};

/// Q of a set of measurements; thresholds apply when given. Throws std::runtime_error("<what>: ...") when
/// fewer than min_samples measurements are usable or Q is not positive definite.
CovarianceEstimate estimateCovariance(const std::vector<MeasurementWithTruth>& measurements,
                                      const NoiseModelEstimationParams& params, bool apply_thresholds,
                                      const std::string& what);

/// Both noise models (odometry: all measurements; loop closures: the good ones).
NoiseModelEstimate estimateNoiseModels(const std::vector<MeasurementWithTruth>& odometry,
                                       const std::vector<MeasurementWithTruth>& loop_closures,
                                       const NoiseModelEstimationParams& params = {});

/// Odometry (BetweenFactorPose3 <r>(i-1) -> <r>i as measurement 0 of its entry) and loop closures (every other
/// BetweenFactorPose3) of a JRL dataset with their reference values from its groundtruth; only `robot`'s measurements
/// when given, all robots' otherwise. Throws std::runtime_error when the dataset has no groundtruth or a key lacks one.
struct MeasurementSets {
  std::vector<MeasurementWithTruth> odometry;
  std::vector<MeasurementWithTruth> loop_closures;
};
MeasurementSets collectMeasurements(const jrl::Dataset& dataset, std::optional<char> robot = std::nullopt);

}  // namespace cosmo::dataset
