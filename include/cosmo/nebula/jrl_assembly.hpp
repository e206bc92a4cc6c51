#pragma once
// A Nebula team graph (nebula/graph_builder.hpp) as a JRL dataset, the way the paper converts the Nebula
// datasets and COSMO-Bench lays its files out (../shared/docs/jrl.md §10):
// - per robot r with poses 0..n-1: entry i stamped with pose i's node stamp; entry 0 holds the prior on r0 at
//   its reference pose (covariance diag(1e-8 x3, 1e-6 x3), as COSMO-Bench), entry i >= 1 the odometry
//   r(i-1) -> r(i) as measurement 0;
// - each loop closure in the entry of the robot and time at which it was made: its later pose's (later stamp;
//   equal stamps: the larger key), with key1 = that pose (the source edge is inverted when it ran the other
//   way: measurement inverted, covariance mapped through the adjoint); keys are the source graph's gtsam keys;
// - covariances: the recorded ones (reordered to rotation first), or one constant model for all odometry and
//   one for all loop closures (given, or estimated from this dataset by the paper's procedure:
//   dataset/noise_model_estimation.hpp, good closures < 0.5 m and < 0.05 rad);
// - every loop closure a potential outlier; outliers by the chi^2 rule (dataset/outlier_rule.hpp) against the
//   reference with the closure's covariance;
// - groundtruth: the reference pose of every key a robot's factors use; initialization: own poses by dead
//   reckoning from the prior, a teammate's key through the first closure of the robot's list that uses it.
#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/jrl/dataset.hpp"
#include "cosmo/nebula/graph_builder.hpp"

namespace cosmo::nebula {

enum class NoiseSource {
  Recorded,   ///< each edge's own covariance from the source graph
  Given,      ///< ConversionParams::models
  Estimated,  ///< estimated from this dataset against its reference
};

struct ConversionParams {
  std::string name = "nebula";
  NoiseSource noise = NoiseSource::Recorded;
  dataset::NoiseModels models;                     ///< used with NoiseSource::Given
  dataset::NoiseModelEstimationParams estimation;  ///< used with NoiseSource::Estimated
  dataset::OutlierRule rule = dataset::OutlierRule::Fidelity;
  double critical_value = dataset::kChi2Critical95Dof6;
};

struct ConversionReport {
  std::optional<dataset::NoiseModelEstimate> estimate;  ///< with NoiseSource::Estimated
  std::optional<dataset::NoiseModels> models;           ///< the constant models used (Given / Estimated)
  std::size_t odometry = 0, intra = 0, inter = 0, intra_outliers = 0, inter_outliers = 0;
  std::size_t inverted = 0;  ///< loop closures stored the other way round (key1 = the later pose)
};

/// The dataset. `reference` holds the reference pose of every robot pose (result.g2o). Throws
/// std::runtime_error naming the keys when reference poses are missing, naming the edge when a recorded
/// covariance is not symmetric positive definite, and as estimateNoiseModels() does.
jrl::Dataset assembleJrl(const NebulaGraph& graph, const std::map<jrl::Key, Pose3>& reference,
                         const ConversionParams& params, ConversionReport* report = nullptr);

}  // namespace cosmo::nebula
