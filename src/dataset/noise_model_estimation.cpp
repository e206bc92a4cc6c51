#include "cosmo/dataset/noise_model_estimation.hpp"

#include <stdexcept>
#include <string>

#include "cosmo/dataset/outlier_rule.hpp"

namespace cosmo::dataset {

CovarianceEstimate estimateCovariance(const std::vector<MeasurementWithTruth>& measurements,
                                      const NoiseModelEstimationParams& params, bool apply_thresholds,
                                      const std::string& what) {
  CovarianceEstimate est;
  std::vector<Vector6> residuals;
  residuals.reserve(measurements.size());
  for (const auto& m : measurements) {
    const Pose3 error = m.measurement.inverse(Eigen::Isometry) * m.truth;
    const Vector6 r = logSE3(error);
    const bool finite = r.allFinite();
    if (!finite || (apply_thresholds && (error.translation().norm() >= params.max_translation_error ||
                                         rotationAngle(error) >= params.max_rotation_error))) {
      ++est.rejected;
      continue;
    }
    residuals.push_back(r);
  }
  est.used = residuals.size();
  const std::size_t needed = std::max<std::size_t>(params.min_samples, params.subtract_mean ? 7 : 6);
  if (est.used < needed)
    throw std::runtime_error(what + ": only " + std::to_string(est.used) + " usable measurements (" +
                             std::to_string(est.rejected) + " over the thresholds), need at least " +
                             std::to_string(needed));
  Vector6 sum = Vector6::Zero();
  for (const auto& r : residuals) sum += r;
  est.mean_residual = sum / static_cast<double>(est.used);
  Matrix6 q = Matrix6::Zero();
  const Vector6 centre = params.subtract_mean ? est.mean_residual : Vector6::Zero();
  for (const auto& r : residuals) q += (r - centre) * (r - centre).transpose();
  q /= static_cast<double>(params.subtract_mean ? est.used - 1 : est.used);
  est.covariance = 0.5 * (q + q.transpose());
  checkCovariance(est.covariance, what);
  return est;
}

NoiseModelEstimate estimateNoiseModels(const std::vector<MeasurementWithTruth>& odometry,
                                       const std::vector<MeasurementWithTruth>& loop_closures,
                                       const NoiseModelEstimationParams& params) {
  NoiseModelEstimate out;
  out.odometry = estimateCovariance(odometry, params, false, "odometry");
  out.loop_closure = estimateCovariance(loop_closures, params, true, "loop closures");
  out.models.odometry = out.odometry.covariance;
  out.models.loop_closure = out.loop_closure.covariance;
  return out;
}

MeasurementSets collectMeasurements(const jrl::Dataset& dataset, std::optional<char> robot) {
  if (!dataset.groundtruth) throw std::runtime_error("dataset '" + dataset.name + "' has no groundtruth");
  MeasurementSets sets;
  for (const char r : dataset.robots) {
    if (robot && r != *robot) continue;
    const auto entries = dataset.measurements.find(r);
    if (entries == dataset.measurements.end()) continue;
    const auto gt = dataset.groundtruth->find(r);
    if (gt == dataset.groundtruth->end())
      throw std::runtime_error("dataset '" + dataset.name + "': no groundtruth for robot " + std::string(1, r));
    for (const auto& entry : entries->second) {
      for (std::size_t i = 0; i < entry.factors.size(); ++i) {
        const jrl::Factor& f = entry.factors[i];
        if (!f.isBetweenPose3() || f.keys.size() != 2) continue;
        const jrl::Key k1 = f.keys[0], k2 = f.keys[1];
        MeasurementWithTruth m;
        m.measurement = f.pose3();
        try {
          m.truth = jrl::pose3At(gt->second, k1).inverse(Eigen::Isometry) * jrl::pose3At(gt->second, k2);
        } catch (const std::out_of_range&) {
          throw std::runtime_error("dataset '" + dataset.name + "': robot " + std::string(1, r) + ": factor " +
                                   jrl::keyName(k1) + " -> " + jrl::keyName(k2) +
                                   " refers to a key without groundtruth");
        }
        // COSMO convention (jrl.md §10): odometry <r>(i-1) -> <r>i is measurement 0 of its entry.
        const bool odometry =
            i == 0 && jrl::robotOf(k1) == r && jrl::robotOf(k2) == r && jrl::indexOf(k2) == jrl::indexOf(k1) + 1;
        (odometry ? sets.odometry : sets.loop_closures).push_back(m);
      }
    }
  }
  return sets;
}

}  // namespace cosmo::dataset
