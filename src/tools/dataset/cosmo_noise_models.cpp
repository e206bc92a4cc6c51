// cosmo_noise_models: estimate the odometry and loop-closure noise models (spec section 6) from a run's JRL
// with ground truth (normally a single-robot run of the environment's designated trial) and write the YAML
// the recorder reads (config/noise_models/<environment>.yaml).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "cosmo/common/command_line.hpp"
#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/jrl/io.hpp"

namespace {

void printEstimate(const char* what, const cosmo::dataset::CovarianceEstimate& e) {
  std::cout << what << ": " << e.used << " used, " << e.rejected
            << " over the thresholds\n  sigmas [rx ry rz tx ty tz]:";
  for (int i = 0; i < 6; ++i) std::cout << ' ' << std::setprecision(4) << std::sqrt(e.covariance(i, i));
  std::cout << "\n  mean residual:";
  for (int i = 0; i < 6; ++i) std::cout << ' ' << std::setprecision(3) << e.mean_residual(i);
  std::cout << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, output, environment;
  std::optional<char> robot;
  cosmo::dataset::NoiseModelEstimationParams params;
  std::string robot_id;
  cosmo::CommandLine app(
      "cosmo_noise_models",
      "Estimates Q = (1/N) sum r r^T, r = Log(m^-1 * m*) (rotation first), for the odometry (every "
      "BetweenFactorPose3 <r>(i-1) -> <r>i) and the good loop closures (every other BetweenFactorPose3 whose error is "
      "under the thresholds) of INPUT.jrl against its groundtruth, and writes OUTPUT.yaml.");
  app.add_option("INPUT.jrl", input, "a run's dataset with ground truth")->required();
  app.add_option("OUTPUT.yaml", output, "the noise models")->required();
  app.add_option("--robot", robot_id,
                 "use only robot R's measurements (default: every robot; a single-robot run "
                 "has one)")
      ->type_name("R")
      ->check([](const std::string& r) { return r.size() == 1 ? "" : "expected one character, got '" + r + "'"; });
  app.add_option("--environment", environment, "label written to the YAML (default: the dataset name)");
  cosmo::addClosureThresholds(app, "max", params.max_translation_error, params.max_rotation_error);
  app.add_flag("--subtract-mean", params.subtract_mean,
               "centred sample covariance (divide by N-1) instead of the second moment");
  app.add_option("--min-samples", params.min_samples, "refuse to estimate from fewer measurements")
      ->capture_default_str()
      ->check(cosmo::Positive);
  if (const std::optional<int> exit_code = app.parseOrExit(argc, argv)) return *exit_code;
  if (!robot_id.empty()) robot = robot_id[0];
  try {
    const cosmo::jrl::Dataset ds = cosmo::jrl::readJrl(input);
    if (robot && std::find(ds.robots.begin(), ds.robots.end(), *robot) == ds.robots.end())
      throw std::runtime_error(input + ": no robot '" + std::string(1, *robot) + "'");
    std::string robots;
    for (const char r : ds.robots)
      if (!robot || r == *robot) robots += std::string(robots.empty() ? "" : " ") + r;
    if (!robot && ds.robots.size() > 1)
      std::cerr << "cosmo_noise_models: warning: pooling robots " << robots
                << " (spec section 6 uses a single-robot run; --robot R picks one)\n";
    const cosmo::dataset::MeasurementSets sets = cosmo::dataset::collectMeasurements(ds, robot);
    cosmo::dataset::NoiseModelEstimate est =
        cosmo::dataset::estimateNoiseModels(sets.odometry, sets.loop_closures, params);
    est.models.environment = environment.empty() ? ds.name : environment;
    est.models.provenance = "estimated by cosmo_noise_models from " + input + " (spec section 6)";
    cosmo::dataset::NoiseModelRecord record;
    record.trial = ds.name + " (" + input + ", robots " + robots + ")";
    record.odometry_factors = est.odometry.used;
    record.loop_closures = est.loop_closure.used;
    record.loop_closures_left_out = est.loop_closure.rejected;
    record.max_translation_error = params.max_translation_error;
    record.max_rotation_error = params.max_rotation_error;
    est.models.estimated_from = record;
    printEstimate("odometry", est.odometry);
    printEstimate("loop closures", est.loop_closure);
    std::ostringstream header;
    header << "Noise models estimated by cosmo_noise_models (spec section 6) from " << input << "\n"
           << "dataset '" << ds.name << "', robots " << robots << ": " << est.odometry.used << " odometry factors, "
           << est.loop_closure.used << " loop closures (" << est.loop_closure.rejected
           << " left out: error >= " << params.max_translation_error << " m or >= " << params.max_rotation_error
           << " rad)\n"
           << "Q = " << (params.subtract_mean ? "centred sample covariance, 1/(N-1)" : "(1/N) sum r r^T")
           << " with r = Log(m^-1 * m*), rotation first";
    est.models.save(output, header.str());
    std::cout << "wrote " << output << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "cosmo_noise_models: " << e.what() << "\n";
    return 1;
  }
}
