// Where a sequence's trials come from: the data root and its precedence, the stamp convention key, the one
// reference offset per sequence, and the shipped COSMO-Bench configs (real file names, topics, conventions and
// extrinsics; the MCD T_body_lidar quaternions checked against the calibration matrices).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cosmo/common/pose_io.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/trials/sequence_metadata.hpp"
#include "cosmo/trials/trial_reference.hpp"

using namespace cosmo;
using namespace cosmo::sequence;
using namespace cosmo::trials;
namespace fs = std::filesystem;

namespace {

fs::path tempDir() {
  const auto dir = fs::temp_directory_path() / "cosmo_sequence_sources_test";
  fs::create_directories(dir);
  return dir;
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const auto path = tempDir() / name;
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path.string();
}

/// Sets an environment variable for the scope.
struct ScopedEnv {
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_)
      setenv(name_, old_.c_str(), 1);
    else
      unsetenv(name_);
  }
  const char* name_;
  std::string old_;
  bool had_ = false;
};

const char* kTwoTrials = R"(
name: roots
trials:
  - robot: a
    bag: ntu_day_01/ntu_day_01_os1_128.bag
    reference: ntu_day_01/pose_inW.csv
  - robot: b
    bag: /abs/b.bag
    stamp: start
noise_models: ../noise_models/ntu.yaml
)";

/// Row-major 3 x 4 T_body_lidar from real_data_formats.md (MCD calibration, as evalio / ceva / slict give it).
constexpr double kAtv[12] = {0.9999346552051229,    0.003477624535771754, -0.010889970036688295, -0.060649229060416594,
                             0.003587143302461965,  -0.9999430279821171,  0.010053516443599904,  -0.012837544242408117,
                             -0.010854387257665576, -0.01009192338171122, -0.999890161647627,    -0.020492606896077407};
constexpr double kHandheld[12] = {0.9999135040741837,   -0.011166365511073898, -0.006949579221822984,
                                  -0.04894521120494695, -0.011356389542502144, -0.9995453006865824,
                                  -0.02793249526856565, -0.03126929060348084,  -0.006634514801117132,
                                  0.02800900135032654,  -0.999585653686922,    -0.01755515794222565};

void expectPoseIsMatrix(const Pose3& p, const double* m, const std::string& where) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(p.linear()(r, c), m[4 * r + c], 1e-9) << where << " R(" << r << "," << c << ")";
    EXPECT_NEAR(p.translation()(r), m[4 * r + 3], 1e-12) << where << " t(" << r << ")";
  }
}

std::string shippedConfig(const std::string& name) {
  return std::string(COSMO_SOURCE_DIR) + "/config/sequences/" + name + ".yaml";
}

}  // namespace

TEST(DataRoot, PrecedenceArgumentThenKeyThenEnvironmentThenConfigFolder) {
  const std::string path = writeTemp("configs/roots.yaml", kTwoTrials);
  const std::string with_key = writeTemp("configs/roots_key.yaml", std::string(kTwoTrials) + "data_root: ../keyed\n");
  const fs::path cfg_dir = fs::path(path).parent_path();
  {
    ScopedEnv env("COSMO_DATA_ROOT", nullptr);
    const auto cfg = SequenceConfig::load(path);
    EXPECT_EQ(cfg.trials[0].bag, (cfg_dir / "ntu_day_01/ntu_day_01_os1_128.bag").string());
    EXPECT_EQ(cfg.data_root_from, "config folder");
    EXPECT_EQ(cfg.trials[1].bag, "/abs/b.bag");  // absolute paths stay
    // the noise models stay relative to the config file, whatever the data root
    EXPECT_EQ(cfg.noise_models, (cfg_dir.parent_path() / "noise_models/ntu.yaml").string());
  }
  {
    ScopedEnv env("COSMO_DATA_ROOT", "/data/env");
    EXPECT_EQ(SequenceConfig::load(path).trials[0].reference, "/data/env/ntu_day_01/pose_inW.csv");
    EXPECT_EQ(SequenceConfig::load(path).data_root_from, "COSMO_DATA_ROOT");
    // the file's key beats the environment, the argument beats both
    EXPECT_EQ(SequenceConfig::load(with_key).trials[0].reference,
              (cfg_dir.parent_path() / "keyed/ntu_day_01/pose_inW.csv").string());
    const auto arg = SequenceConfig::load(with_key, "/data/arg");
    EXPECT_EQ(arg.trials[0].bag, "/data/arg/ntu_day_01/ntu_day_01_os1_128.bag");
    EXPECT_EQ(arg.data_root_from, "argument");
    EXPECT_EQ(arg.noise_models, (cfg_dir.parent_path() / "noise_models/ntu.yaml").string());
  }
}

TEST(StampKey, StartEndDefaultAndErrors) {
  const auto cfg = SequenceConfig::load(writeTemp("stamp_ok.yaml", kTwoTrials));
  EXPECT_TRUE(cfg.trials[0].stamp_at_end);  // default: end
  EXPECT_FALSE(cfg.trials[1].stamp_at_end);
  const std::string bad =
      writeTemp("stamp_bad.yaml", "name: x\ntrials:\n  - robot: a\n    bag: a.bag\n    stamp: middle\n");
  try {
    SequenceConfig::load(bad);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("trials[0].stamp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("middle"), std::string::npos) << e.what();
  }
}

TEST(ReferenceOffset, OneOffsetPerSequenceFromTheAnchor) {
  // two robots in one UTM frame (CU-Multi): the anchor's first position, rounded, comes off both
  writeTemp("utm/r1.csv",
            "num,t,x,y,z,qx,qy,qz,qw\n1,100.0,477146.28,4428491.09,1630.57,0,0,0,1\n"
            "2,100.1,477147.28,4428491.09,1630.57,0,0,0,1\n");
  writeTemp("utm/r2.csv",
            "num,t,x,y,z,qx,qy,qz,qw\n1,200.0,477000.50,4428400.25,1629.00,0,0,0,1\n"
            "2,200.1,477001.50,4428400.25,1629.00,0,0,0,1\n");
  const std::string path = writeTemp("utm/seq.yaml", R"(
name: utm
anchor: b
reference_offset: anchor
trials:
  - robot: a
    bag: a.bag
    reference: r1.csv
  - robot: b
    bag: b.bag
    reference: r2.csv
)");
  ScopedEnv env("COSMO_DATA_ROOT", nullptr);
  const auto cfg = SequenceConfig::load(path);
  const Eigen::Vector3d offset = sequenceReferenceOffset(cfg);
  EXPECT_EQ(offset, Eigen::Vector3d(477001.0, 4428400.0, 1629.0));  // anchor b's first position, whole metres
  TrialTiming timing;
  const Trajectory a = loadSensorReference(cfg.trial('a'), timing, offset);
  const Trajectory b = loadSensorReference(cfg.trial('b'), timing, offset);
  // the robots keep their relative placement (one frame), near the origin
  EXPECT_NEAR(
      (a.poses()[0].pose.translation() - b.poses()[0].pose.translation()).norm(),
      (Eigen::Vector3d(477146.28, 4428491.09, 1630.57) - Eigen::Vector3d(477000.50, 4428400.25, 1629.00)).norm(), 1e-6);
  EXPECT_LT(b.poses()[0].pose.translation().norm(), 1.0);

  const std::string fixed =
      writeTemp("utm/fixed.yaml", "name: f\nreference_offset: [1, 2, 3]\ntrials:\n  - robot: a\n    bag: a.bag\n");
  EXPECT_EQ(sequenceReferenceOffset(SequenceConfig::load(fixed)), Eigen::Vector3d(1, 2, 3));
  const std::string none = writeTemp("utm/none.yaml", "name: n\ntrials:\n  - robot: a\n    bag: a.bag\n");
  EXPECT_EQ(sequenceReferenceOffset(SequenceConfig::load(none)), Eigen::Vector3d::Zero());
}

TEST(ShippedSequences, McdConfigsNameTheRealFilesAndCalibration) {
  ScopedEnv env("COSMO_DATA_ROOT", nullptr);
  for (const std::string name : {"ntu_r3_00", "ntu_r3_01", "ntu_r3_02", "ntu_r4_00", "ntu_r5_00", "kth_r3_00",
                                 "kth_r3_01", "kth_r4_00", "tuhh_r3_00", "tuhh_r3_01"}) {
    const auto cfg = SequenceConfig::load(shippedConfig(name), "/data/mcd");
    EXPECT_EQ(cfg.name, name);
    EXPECT_EQ(cfg.source, "MCD");
    const bool ntu = name.rfind("ntu", 0) == 0;
    for (const auto& t : cfg.trials) {
      const std::string where = name + " " + t.name;
      EXPECT_EQ(t.bag, "/data/mcd/" + t.name + "/" + t.name + (ntu ? "_os1_128.bag" : "_os1_64.bag")) << where;
      EXPECT_EQ(t.reference, "/data/mcd/" + t.name + "/pose_inW.csv") << where;
      EXPECT_EQ(t.topic, "/os_cloud_node/points") << where;
      EXPECT_TRUE(t.stamp_at_end) << where;
      EXPECT_EQ(t.name.rfind(name.substr(0, name.find('_')) + "_", 0), 0u) << where;
      expectPoseIsMatrix(t.extrinsic, ntu ? kAtv : kHandheld, where);
    }
  }
}

TEST(ShippedSequences, CuMultiConfigsNameTheRealFiles) {
  ScopedEnv env("COSMO_DATA_ROOT", nullptr);
  for (const std::string site : {"kittredge_loop", "main_campus"}) {
    const auto cfg = SequenceConfig::load(shippedConfig(site), "/data/cu");
    EXPECT_EQ(cfg.source, "CU-Multi");
    EXPECT_EQ(cfg.reference_offset.mode, ReferenceOffsetConfig::Mode::Anchor);
    ASSERT_EQ(cfg.trials.size(), 4u);
    for (int i = 0; i < 4; ++i) {
      const auto& t = cfg.trials[i];
      const std::string robot = "robot" + std::to_string(i + 1);
      EXPECT_EQ(t.name, site + "_" + robot);
      EXPECT_EQ(t.bag, "/data/cu/" + site + "/" + robot + "/" + robot + "_" + site + "_lidar");
      EXPECT_EQ(t.reference, "/data/cu/" + site + "/" + robot + "/" + site + "_" + robot + "_ref.csv");
      EXPECT_EQ(t.topic, robot + "/ouster/points");
      EXPECT_FALSE(t.stamp_at_end);
      // imu_T_lidar: 180 deg yaw and the offset
      EXPECT_NEAR(t.extrinsic.translation().x(), -0.058038, 1e-12);
      EXPECT_NEAR(t.extrinsic.translation().z(), 0.049603, 1e-12);
      EXPECT_NEAR(t.extrinsic.linear()(0, 0), -1.0, 1e-12);
      EXPECT_NEAR(t.extrinsic.linear()(2, 2), 1.0, 1e-12);
    }
  }
}

TEST(SequenceMetadata, NamesTheSequencesOwnRegistrationKeysOnlyWhenItHasAny) {
  auto lineOf = [](const std::vector<std::pair<std::string, std::string>>& lines, const std::string& key) {
    for (const auto& [k, v] : lines)
      if (k == key) return v;
    return std::string("(none)");
  };
  const auto plain = SequenceConfig::load(writeTemp("meta_plain.yaml", kTwoTrials));
  EXPECT_EQ(lineOf(sequenceMetadata(plain), "registration"), "(none)");
  const auto paper = SequenceConfig::load(
      writeTemp("meta_paper.yaml", std::string("registration:\n  refine: false\n  gate: paper\n") + kTwoTrials));
  const std::string line = lineOf(sequenceMetadata(paper), "registration");
  EXPECT_EQ(line.substr(0, line.find("  #")), "{gate: paper, refine: false}");
  EXPECT_EQ(lineOf(sequenceMetadata(paper), "sequence"), "roots");
}
