// Noise models: YAML reading/writing, the environment configs, and the estimation recovering a known
// covariance from a synthetic single-robot run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/noise_model_estimation.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/jrl/io.hpp"
#include "synthetic_team.hpp"

using namespace cosmo;
using jrl::symbol;

namespace {

std::filesystem::path tempDir() {
  const auto dir = std::filesystem::temp_directory_path() / ("cosmo_noise_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

ConfigNode parse(const std::string& text) { return ConfigNode{YAML::Load(text), "test.yaml: "}; }

// |Q_hat - Q| within k standard errors of a sample second moment, entry by entry.
void expectWithinSamplingError(const Matrix6& est, const Matrix6& truth, std::size_t n, double k, const char* what) {
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const double se = std::sqrt((truth(i, i) * truth(j, j) + truth(i, j) * truth(i, j)) / static_cast<double>(n));
      EXPECT_NEAR(est(i, j), truth(i, j), k * se) << what << " (" << i << "," << j << ")";
    }
}

// A single robot driving many laps with odometry noise Q_odo and loop closures with noise Q_lc, a tenth of
// them gross errors; written as a JRL (what cosmo_noise_models reads).
jrl::Dataset singleRobotRun(const Matrix6& q_odo, const Matrix6& q_lc, std::size_t n, std::uint64_t seed) {
  test::TangentSampler sampler(seed);
  dataset::DatasetRecorder rec("single", {'a'}, dataset::NoiseModels{});
  std::vector<Pose3> truth;
  for (std::size_t i = 0; i < n; ++i) {
    const double phase = 2 * M_PI * static_cast<double>(i) / 40.0;
    truth.push_back(test::circlePose(phase, 0.001 * static_cast<double>(i)));
    const Pose3 odo = i ? sampler.perturb(truth[i - 1].inverse(Eigen::Isometry) * truth[i], q_odo) : Pose3::Identity();
    rec.addKeyframe('a', i, 1000000000ULL * (i + 1), odo, truth[i]);
    if (i >= 40) {
      Pose3 m = sampler.perturb(truth[i].inverse(Eigen::Isometry) * truth[i - 40], q_lc);
      if (i % 10 == 0) m = m * test::grossError();
      rec.addLoopClosure({'a', 1000000000ULL * (i + 1), symbol('a', i), symbol('a', i - 40), m});
    }
  }
  return rec.build();
}

}  // namespace

TEST(NoiseModels, DefaultsAreValidAndRoundTripThroughYaml) {
  const dataset::NoiseModels d;
  EXPECT_NO_THROW(dataset::checkCovariance(d.odometry, "odometry"));
  EXPECT_NO_THROW(dataset::checkCovariance(d.loop_closure, "loop_closure"));
  EXPECT_DOUBLE_EQ(d.odometry(0, 0), 8.664332784342755e-05);  // the reference file's stored value
  const auto dir = tempDir();
  const std::string path = (dir / "nm.yaml").string();
  dataset::NoiseModels m;
  m.environment = "unit \"test\"";
  m.odometry(1, 2) = m.odometry(2, 1) = 1.0 / 3.0 * 1e-5;
  m.save(path, "line one\nline two");
  const dataset::NoiseModels back = dataset::NoiseModels::load(path);
  EXPECT_EQ(back.odometry, m.odometry);  // bit for bit
  EXPECT_EQ(back.loop_closure, m.loop_closure);
  EXPECT_EQ(back.environment, m.environment);
  std::filesystem::remove_all(dir);
}

TEST(NoiseModels, ReadsFlatListsAndSigmas) {
  const dataset::NoiseModels m = dataset::NoiseModels::fromConfig(parse(
      "odometry:\n  sigmas: [0.01, 0.01, 0.01, 0.1, 0.1, 0.1]\n"
      "loop_closure:\n  covariance: [1,0,0,0,0,0, 0,1,0,0,0,0, 0,0,1,0,0,0, 0,0,0,2,0,0, 0,0,0,0,2,0, 0,0,0,0,0,2]\n"));
  EXPECT_DOUBLE_EQ(m.odometry(0, 0), 1e-4);
  EXPECT_DOUBLE_EQ(m.odometry(5, 5), 0.01);
  EXPECT_EQ(m.odometry(0, 1), 0.0);
  EXPECT_EQ(m.loop_closure(3, 3), 2.0);
  // Both sections are required: nothing is filled in from elsewhere.
  EXPECT_THROW(dataset::NoiseModels::fromConfig(parse("environment: x\n")), std::runtime_error);
  EXPECT_THROW(dataset::NoiseModels::fromConfig(parse("odometry:\n  sigmas: [1, 1, 1, 1, 1, 1]\n")),
               std::runtime_error);
}

TEST(NoiseModels, ProvenanceAndEstimationRecordRoundTrip) {
  dataset::NoiseModels m;
  m.environment = "env";
  m.provenance = "from \"somewhere\"";
  dataset::NoiseModelRecord r;
  r.trial = "night_04";
  r.odometry_factors = 238;
  r.loop_closures = 119;
  r.loop_closures_left_out = 3;
  r.max_translation_error = 0.4;
  r.max_rotation_error = 0.03;
  m.estimated_from = r;
  const dataset::NoiseModels back = dataset::NoiseModels::fromConfig(parse(m.toYaml("header")));
  EXPECT_EQ(back.provenance, m.provenance);
  ASSERT_TRUE(back.estimated_from.has_value());
  EXPECT_EQ(back.estimated_from->trial, "night_04");
  EXPECT_EQ(back.estimated_from->odometry_factors, 238u);
  EXPECT_EQ(back.estimated_from->loop_closures, 119u);
  EXPECT_EQ(back.estimated_from->loop_closures_left_out, 3u);
  EXPECT_EQ(back.estimated_from->max_translation_error, 0.4);
  EXPECT_EQ(back.estimated_from->max_rotation_error, 0.03);
  EXPECT_NE(back.describe().find("estimated from night_04: 238 odometry factors, 119 loop closures"), std::string::npos)
      << back.describe();
  // An environment whose models are unknown says so instead of handing out numbers.
  try {
    dataset::NoiseModels::fromConfig(parse("environment: far\nunknown: \"not measured\"\n"));
    FAIL() << "no error";
  } catch (const dataset::NoiseModelsUnknown& e) { EXPECT_EQ(e.reason, "not measured"); }
}

TEST(NoiseModels, BadConfigsNameFileAndKey) {
  auto message = [](const std::string& text) {
    try {
      dataset::NoiseModels::fromConfig(parse(text));
    } catch (const std::runtime_error& e) { return std::string(e.what()); }
    return std::string("no error");
  };
  EXPECT_NE(message("odometry:\n  covariance: [1, 2, 3]\n").find("test.yaml: odometry.covariance: expected 36"),
            std::string::npos);
  EXPECT_NE(message("odometry:\n  sigmas: [1, 2, x, 4, 5, 6]\n").find("odometry.sigmas[2]"), std::string::npos);
  const std::string odometry = "odometry:\n  sigmas: [1, 1, 1, 1, 1, 1]\n";
  EXPECT_NE(message(odometry + "loop_closure:\n  sigmas: [1, 2, 0, 4, 5, 6]\n").find("positive definite"),
            std::string::npos);
  EXPECT_NE(message(odometry + "loop_closure:\n  nothing: 1\n").find("loop_closure: expected 'covariance'"),
            std::string::npos);
  EXPECT_NE(message(odometry).find("test.yaml: loop_closure: missing"), std::string::npos) << message(odometry);
  std::string asym =
      "odometry:\n  covariance: [1,0.5,0,0,0,0, 0,1,0,0,0,0, 0,0,1,0,0,0, 0,0,0,1,0,0, 0,0,0,0,1,0, 0,0,0,0,0,1]\n";
  EXPECT_NE(message(asym).find("not symmetric"), std::string::npos);
  EXPECT_THROW(dataset::NoiseModels::load("/nonexistent/noise.yaml"), std::runtime_error);
}

TEST(NoiseModels, EnvironmentConfigsLoad) {
  for (const char* env : {"synthetic", "ntu", "kth", "tuhh"}) {
    const std::string path = std::string(COSMO_SOURCE_DIR) + "/config/noise_models/" + env + ".yaml";
    dataset::NoiseModels m;
    ASSERT_NO_THROW(m = dataset::NoiseModels::load(path)) << path;
    EXPECT_EQ(m.environment, env);
  }
  // tuhh = the covariances stored in the reference COSMO-Bench file.
  const dataset::NoiseModels tuhh =
      dataset::NoiseModels::load(std::string(COSMO_SOURCE_DIR) + "/config/noise_models/tuhh.yaml");
  EXPECT_EQ(tuhh.odometry, dataset::NoiseModels::defaultOdometry());
  EXPECT_EQ(tuhh.loop_closure, dataset::NoiseModels::defaultLoopClosure());
  // CU Boulder's are not known: its file says so (no copy of another environment's).
  EXPECT_THROW(dataset::NoiseModels::load(std::string(COSMO_SOURCE_DIR) + "/config/noise_models/cu_boulder.yaml"),
               dataset::NoiseModelsUnknown);
}

TEST(NoiseModels, ShippedModelsAreTheReleasedCosmoBenchCovariances) {
  const auto json_path = sharedPath("ref/cosmo_noise_models.json");
  if (!json_path) GTEST_SKIP() << "../shared/ref/cosmo_noise_models.json absent";
  const nlohmann::json ref = nlohmann::json::parse(std::ifstream(*json_path));
  for (const char* env : {"ntu", "kth", "tuhh"}) {
    const dataset::NoiseModels m =
        dataset::NoiseModels::load(std::string(COSMO_SOURCE_DIR) + "/config/noise_models/" + env + ".yaml");
    EXPECT_FALSE(m.provenance.empty()) << env;
    for (const auto& [key, cov] :
         {std::pair{"odometry_covariance", m.odometry}, std::pair{"loop_closure_covariance", m.loop_closure}}) {
      const auto& v = ref.at(env).at(key);
      ASSERT_EQ(v.size(), 36u);
      for (int i = 0; i < 36; ++i) EXPECT_EQ(cov(i / 6, i % 6), v[i].get<double>()) << env << " " << key << " " << i;
    }
  }
  // Different environments, different models.
  EXPECT_NE(dataset::NoiseModels::load(std::string(COSMO_SOURCE_DIR) + "/config/noise_models/ntu.yaml").loop_closure,
            dataset::NoiseModels::load(std::string(COSMO_SOURCE_DIR) + "/config/noise_models/kth.yaml").loop_closure);
}

TEST(NoiseModelEstimation, RecoversKnownCovarianceFromASyntheticRun) {
  // Dense "true" covariances: the reference file's (realistic magnitudes and correlations).
  const Matrix6 q_odo = dataset::NoiseModels::defaultOdometry(), q_lc = dataset::NoiseModels::defaultLoopClosure();
  const std::size_t n = 4000;
  const jrl::Dataset run = jrl::parseJrl(jrl::dumpJrl(singleRobotRun(q_odo, q_lc, n, 11)));
  const dataset::MeasurementSets sets = dataset::collectMeasurements(run);
  ASSERT_EQ(sets.odometry.size(), n - 1);
  ASSERT_EQ(sets.loop_closures.size(), n - 40);
  const dataset::NoiseModelEstimate est = estimateNoiseModels(sets.odometry, sets.loop_closures);
  EXPECT_EQ(est.odometry.used, n - 1);
  EXPECT_EQ(est.odometry.rejected, 0u);
  const std::size_t gross = (n - 40) / 10;  // i % 10 == 0 for i in [40, n)
  EXPECT_EQ(est.loop_closure.rejected, gross);
  EXPECT_EQ(est.loop_closure.used, n - 40 - gross);
  expectWithinSamplingError(est.models.odometry, q_odo, est.odometry.used, 4.5, "odometry");
  expectWithinSamplingError(est.models.loop_closure, q_lc, est.loop_closure.used, 4.5, "loop closure");
  // Relative error of the variances: a few percent at this sample size.
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(est.models.loop_closure(i, i) / q_lc(i, i), 1.0, 0.1) << i;
  // The centred variant is nearly the same here (zero-mean noise).
  dataset::NoiseModelEstimationParams centred;
  centred.subtract_mean = true;
  const dataset::NoiseModelEstimate c = estimateNoiseModels(sets.odometry, sets.loop_closures, centred);
  EXPECT_LT((c.models.odometry - est.models.odometry).cwiseAbs().maxCoeff(), 0.01 * q_odo.cwiseAbs().maxCoeff());
}

TEST(NoiseModelEstimation, TooFewMeasurementsIsAClearError) {
  std::vector<dataset::MeasurementWithTruth> few(3);
  try {
    estimateNoiseModels(few, few);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("odometry: only 3 usable measurements"), std::string::npos) << e.what();
  }
  // Identical measurements give a singular Q: refused, not written.
  std::vector<dataset::MeasurementWithTruth> same(20);
  EXPECT_THROW(estimateNoiseModels(same, same), std::runtime_error);
  jrl::Dataset no_gt;
  no_gt.name = "x";
  EXPECT_THROW(dataset::collectMeasurements(no_gt), std::runtime_error);
}
