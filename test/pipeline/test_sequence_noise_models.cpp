// The noise models of a run: a sequence without them stops with a message that says how to make them; the
// paper's single-trial step (estimateTrialNoiseModels) on a CI-sized trial writes models whose sigmas lie within
// the spread of the loop closures it saw, and whose outlier labels separate good closures from wrong ones.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/sequence_noise_models.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/pipeline/trial_noise_models.hpp"
#include "../support/synthetic_team.hpp"

using namespace cosmo;
using namespace cosmo::pipeline;
using namespace cosmo::sequence;

namespace {

std::filesystem::path tempDir() {
  const auto dir = std::filesystem::temp_directory_path() / ("cosmo_seq_noise_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

SequenceConfig sequenceWith(const std::string& environment, const std::string& noise_models) {
  SequenceConfig s;
  s.path = "/data/my_sequence.yaml";
  s.name = "my_sequence";
  s.environment = environment;
  s.noise_models = noise_models;
  TrialConfig a, b;
  a.robot = 'a';
  a.name = "walk_1";
  b.robot = 'b';
  b.name = "walk_2";
  s.trials = {a, b};
  return s;
}

std::string missingMessage(const SequenceConfig& s, const std::string& config_dir) {
  try {
    loadSequenceNoiseModels(s, config_dir);
  } catch (const NoiseModelsMissing& e) { return e.what(); }
  return "no NoiseModelsMissing";
}

/// One CI-sized trial that comes back to where it started: an ATV once around a block of the CI campus and on
/// along its first side again (its own loop closures), with the light 32 x 512 LiDAR of the pipeline tests.
test::SyntheticTrial loopTrial() {
  sim::SimulationParams params = sim::SimulationParams::load(std::string(COSMO_SOURCE_DIR) + "/config/sim/ci.yaml");
  const sim::LidarModel full = params.lidar;
  params.lidar = sim::LidarModel::os1_32();
  params.lidar.columns = 512;
  params.lidar.range_sigma_per_m = full.range_sigma_per_m;
  params.lidar.beam_angle_sigma_deg = full.beam_angle_sigma_deg;
  sim::TrialParams t;
  t.robot = "a";
  t.name = "loop_a";
  t.platform = "atv";
  t.start_node = 0;
  t.route.waypoints = {1, 4, 3, 0, 1};
  t.motion.start_still = 0.5;
  t.motion.end_still = 0.5;
  params.trials = {t};
  return test::simulateSingleTrial(params);
}

}  // namespace

TEST(SequenceNoiseModels, ASequenceWithoutNoiseModelsStopsWithTheWayToMakeThem) {
  const std::string config_dir = std::string(COSMO_SOURCE_DIR) + "/config";
  // Names none: no silent synthetic default.
  const std::string none = missingMessage(sequenceWith("", ""), config_dir);
  EXPECT_NE(none.find("/data/my_sequence.yaml: names no noise models"), std::string::npos) << none;
  // An environment without a file.
  const std::string absent = missingMessage(sequenceWith("mars", ""), config_dir);
  EXPECT_NE(absent.find("environment 'mars' do not exist"), std::string::npos) << absent;
  EXPECT_NE(absent.find(config_dir + "/noise_models/mars.yaml"), std::string::npos) << absent;
  // CU Boulder: shipped as unknown, not as another environment's copy.
  const std::string unknown = missingMessage(sequenceWith("cu_boulder", ""), config_dir);
  EXPECT_NE(unknown.find("are not known"), std::string::npos) << unknown;
  for (const std::string& m : {none, absent, unknown}) {
    EXPECT_NE(m.find("--estimate-noise-models TRIAL"), std::string::npos) << m;
    EXPECT_NE(m.find("a (walk_1), b (walk_2)"), std::string::npos) << m;
    EXPECT_NE(m.find("cosmo_noise_models RUN.jrl"), std::string::npos) << m;
  }
  // The ROS run's resolution says the same.
  EXPECT_THROW(loadRunNoiseModels("", "", "", config_dir), NoiseModelsMissing);
  EXPECT_THROW(loadRunNoiseModels("/nonexistent/noise.yaml", "", "", config_dir), NoiseModelsMissing);
  // What a sequence names is what it gets; an explicit file overrides it.
  const dataset::NoiseModels ntu = loadSequenceNoiseModels(sequenceWith("ntu", ""), config_dir);
  EXPECT_EQ(ntu.environment, "ntu");
  EXPECT_EQ(ntu.source, config_dir + "/noise_models/ntu.yaml");
  EXPECT_NE(ntu.provenance.find("COSMO-Bench"), std::string::npos);
  EXPECT_EQ(loadSequenceNoiseModels(sequenceWith("ntu", config_dir + "/noise_models/kth.yaml"), config_dir).environment,
            "kth");
  EXPECT_EQ(
      loadSequenceNoiseModels(sequenceWith("ntu", ""), config_dir, config_dir + "/noise_models/tuhh.yaml").environment,
      "tuhh");
  EXPECT_EQ(loadRunNoiseModels("", "", config_dir + "/sim/ci.yaml", config_dir).environment, "synthetic");
  EXPECT_EQ(findTrial(sequenceWith("", ""), "b").name, "walk_2");
  EXPECT_EQ(findTrial(sequenceWith("", ""), "walk_1").robot, 'a');
  EXPECT_THROW(findTrial(sequenceWith("", ""), "c"), std::runtime_error);
}

TEST(TrialNoiseModels, EstimateFromOneTrialAloneFitsTheClosuresItSawAndLabelsThem) {
  const test::SyntheticTrial trial = loopTrial();
  std::vector<TrialSpan> spans{{trial.robot, trial.scans.front().stamp, trial.scans.back().stamp}};
  const SequenceTiming timing = SequenceTiming::synchronize(spans, trial.robot, 0.0, 1);
  const Trajectory reference = toSensorReference(trial.body, trial.extrinsic, timing.of(trial.robot));
  std::map<char, std::unique_ptr<ScanSource>> sources;
  sources[trial.robot] = std::make_unique<VectorScanSource>(trial.scans);
  MergedScanStream stream(std::move(sources), timing);
  TeamRunParams params;
  params.frontend = frontend::FrontendParams::loadDir(defaultConfigDir());
  dataset::NoiseModelEstimationParams estimation;
  estimation.min_samples = 6;
  const TrialNoiseModels result =
      estimateTrialNoiseModels(trial.robot, stream, reference, params, 5, estimation, "test_a", "ci");

  // The file records the trial, the counts and the thresholds, and reads back bit for bit.
  const auto dir = tempDir();
  const std::string path = (dir / "ci.yaml").string();
  result.estimate.models.save(path, "test");
  const dataset::NoiseModels back = dataset::NoiseModels::load(path);
  EXPECT_EQ(back.loop_closure, result.estimate.models.loop_closure);
  EXPECT_EQ(back.environment, "ci");
  ASSERT_TRUE(back.estimated_from.has_value());
  EXPECT_EQ(back.estimated_from->trial, "test_a");
  EXPECT_EQ(back.estimated_from->loop_closures, result.estimate.loop_closure.used);
  EXPECT_EQ(back.estimated_from->odometry_factors, result.estimate.odometry.used);
  EXPECT_DOUBLE_EQ(back.estimated_from->max_translation_error, 0.5);
  EXPECT_DOUBLE_EQ(back.estimated_from->max_rotation_error, 0.05);
  std::filesystem::remove_all(dir);

  // Every sigma lies within the spread of the good closures' residuals on its axis.
  const dataset::MeasurementSets sets = dataset::collectMeasurements(result.run, trial.robot);
  std::vector<Vector6> good;
  std::vector<dataset::MeasurementWithTruth> good_closures;
  for (const auto& m : sets.loop_closures) {
    const Pose3 e = m.measurement.inverse(Eigen::Isometry) * m.truth;
    if (e.translation().norm() < 0.5 && rotationAngle(e) < 0.05) {
      good.push_back(dataset::measurementResidual(m.measurement, m.truth));
      good_closures.push_back(m);
    }
  }
  ASSERT_EQ(good.size(), result.estimate.loop_closure.used);
  ASSERT_GE(good.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    double lo = 1e9, hi = 0.0;
    for (const auto& r : good) {
      lo = std::min(lo, std::abs(r(i)));
      hi = std::max(hi, std::abs(r(i)));
    }
    const double sigma = std::sqrt(result.estimate.models.loop_closure(i, i));
    EXPECT_GE(sigma, lo) << "axis " << i;
    EXPECT_LE(sigma, hi) << "axis " << i;
  }

  // Labels with the estimated models: >= 90 % of the good closures are inliers, and every closure off by more
  // than 2 m is an outlier (the good ones displaced as a registration onto the wrong façade would be).
  const Matrix6& q = result.estimate.models.loop_closure;
  std::size_t inliers = 0;
  for (const auto& m : good_closures) inliers += dataset::isOutlier(m.measurement, m.truth, q) ? 0 : 1;
  EXPECT_GE(static_cast<double>(inliers), 0.9 * static_cast<double>(good_closures.size()));
  for (const auto& m : sets.loop_closures)
    if ((m.measurement.inverse(Eigen::Isometry) * m.truth).translation().norm() > 2.0)
      EXPECT_TRUE(dataset::isOutlier(m.measurement, m.truth, q));
  for (const auto& m : good_closures) {
    Pose3 shifted = m.measurement;
    shifted.translation() += Eigen::Vector3d(2.1, 0.0, 0.0);
    EXPECT_TRUE(dataset::isOutlier(shifted, m.truth, q));
  }
}
