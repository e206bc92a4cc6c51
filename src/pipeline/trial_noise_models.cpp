#include "cosmo/pipeline/trial_noise_models.hpp"

#include <sstream>

namespace cosmo::pipeline {
namespace {

/// The single-trial run: the robot's scans through its front-end, everything recorded.
jrl::Dataset runAlone(char robot, sequence::MergedScanStream& stream, const Trajectory& reference, const TeamRunParams& params,
                      std::uint64_t radio_seed, const std::string& name) {
  TeamRun run(name, {{robot, reference}}, params, radio_seed, stream.timing().start());
  char r;
  Scan scan;
  StampNs last = stream.timing().start();
  while (stream.next(r, scan)) {
    if (r != robot)
      throw std::runtime_error("estimateTrialNoiseModels: the stream has scans of robot " + std::string(1, r) +
                               ", expected only " + std::string(1, robot));
    last = scan.stamp;
    run.add(r, frontend::OwnScan::of(scan));
  }
  run.finish(last);
  return run.recorder().build();
}

dataset::NoiseModelRecord recordOf(const dataset::NoiseModelEstimate& e, const dataset::NoiseModelEstimationParams& p, const std::string& trial) {
  dataset::NoiseModelRecord r;
  r.trial = trial;
  r.odometry_factors = e.odometry.used;
  r.loop_closures = e.loop_closure.used;
  r.loop_closures_left_out = e.loop_closure.rejected;
  r.max_translation_error = p.max_translation_error;
  r.max_rotation_error = p.max_rotation_error;
  return r;
}

}  // namespace

TrialNoiseModels estimateTrialNoiseModels(char robot, sequence::MergedScanStream& stream, const Trajectory& reference,
                                          const TeamRunParams& params, std::uint64_t radio_seed,
                                          const dataset::NoiseModelEstimationParams& estimation, const std::string& trial_label,
                                          const std::string& environment) {
  TrialNoiseModels out;
  out.run = runAlone(robot, stream, reference, params, radio_seed, trial_label + "_alone");
  const dataset::MeasurementSets sets = dataset::collectMeasurements(out.run, robot);
  try {
    out.estimate = estimateNoiseModels(sets.odometry, sets.loop_closures, estimation);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("noise models from trial " + trial_label + " run alone (" +
                             std::to_string(sets.odometry.size()) + " odometry factors, " +
                             std::to_string(sets.loop_closures.size()) + " loop closures): " + e.what());
  }
  dataset::NoiseModels& m = out.estimate.models;
  m.environment = environment;
  m.estimated_from = recordOf(out.estimate, estimation, trial_label);
  std::ostringstream provenance;
  provenance << "estimated from trial " << trial_label << " run alone through the front-end ("
             << (params.frontend.odometry == frontend::OdometryKind::Reference ? "reference" : "LOAM") << " odometry), spec section 6";
  m.provenance = provenance.str();
  return out;
}

}  // namespace cosmo::pipeline
