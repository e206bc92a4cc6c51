// DatasetRecorder on a synthetic 2-robot team: the COSMO conventions of ../shared/docs/jrl.md §10.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/jrl/stats.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"
#include "synthetic_team.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
using cosmo::jrl::symbol;

namespace {

const Matrix6 kOdoCov = test::diagonalCovariance(0.002, 0.02);
const Matrix6 kLcCov = test::diagonalCovariance(0.004, 0.05);

dataset::NoiseModels models() {
  dataset::NoiseModels m;
  m.odometry = kOdoCov;
  m.loop_closure = kLcCov;
  m.environment = "test";
  return m;
}

double poseDistance(const Pose3& a, const Pose3& b) { return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff(); }

class RecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    team = test::makeTeam(kOdoCov, kLcCov, 7);
    test::feed(rec, team);
    ds = rec.build(&report);
  }
  test::SyntheticTeam team;
  dataset::DatasetRecorder rec{"synthetic_team", {'a', 'b'}, models()};
  dataset::BuildReport report;
  jrl::Dataset ds;
};

}  // namespace

TEST_F(RecorderTest, PriorAndOdometryEntries) {
  for (const auto& v : jrl::validate(ds)) ADD_FAILURE() << v.str();
  ASSERT_EQ(ds.robots, (std::vector<char>{'a', 'b'}));
  EXPECT_EQ(ds.name, "synthetic_team");
  for (const char r : {'a', 'b'}) {
    const auto& entries = ds.measurements.at(r);
    const std::size_t n = team.truth[r].size();
    ASSERT_GE(entries.size(), n);
    // Entry 0: exactly the prior at the reference pose of <r>0 (plus nothing else in this scenario).
    ASSERT_EQ(entries[0].factors.size(), 1u);
    const jrl::Factor& prior = entries[0].factors[0];
    EXPECT_TRUE(prior.isPriorPose3());
    EXPECT_EQ(prior.keys, std::vector<jrl::Key>{symbol(r, 0)});
    EXPECT_LT(poseDistance(prior.pose3(), team.truth[r][0]), 1e-12);
    EXPECT_TRUE(prior.covarianceMatrix().isApprox(dataset::priorCovariance(), 0.0));
    EXPECT_DOUBLE_EQ(prior.covarianceMatrix()(0, 0), 1e-8);
    EXPECT_DOUBLE_EQ(prior.covarianceMatrix()(5, 5), 1e-6);
    // Entry i: odometry (i-1) -> i first, at keyframe i's stamp.
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(entries[i].stamp, team.stamps[r][i]);
      if (i == 0) continue;
      const jrl::Factor& odo = entries[i].factors.at(0);
      EXPECT_TRUE(odo.isBetweenPose3());
      EXPECT_EQ(odo.keys, (std::vector<jrl::Key>{symbol(r, i - 1), symbol(r, i)}));
      EXPECT_TRUE(odo.covarianceMatrix().isApprox(kOdoCov, 0.0));
    }
    for (std::size_t e = 1; e < entries.size(); ++e) EXPECT_LT(entries[e - 1].stamp, entries[e].stamp) << r << e;
  }
}

TEST_F(RecorderTest, LoopClosuresInTheirEntries) {
  std::size_t found = 0;
  for (const auto& c : team.closures) {
    const char owner = c.lc.owner;
    const auto& entries = ds.measurements.at(owner);
    ASSERT_LT(c.expected_entry, entries.size()) << jrl::keyName(c.lc.key1) << "->" << jrl::keyName(c.lc.key2);
    // Normalised keys: key1 owned (the newer pose for intra-robot closures).
    jrl::Key k1 = c.lc.key1, k2 = c.lc.key2;
    Pose3 m = c.lc.measurement;
    const bool swap = jrl::robotOf(k1) != owner || (jrl::robotOf(k2) == owner && jrl::indexOf(k2) > jrl::indexOf(k1));
    if (swap) {
      std::swap(k1, k2);
      m = m.inverse(Eigen::Isometry);
    }
    bool here = false;
    const auto& factors = entries[c.expected_entry].factors;
    for (std::size_t j = 0; j < factors.size(); ++j) {
      if (factors[j].keys != std::vector<jrl::Key>{k1, k2} || poseDistance(factors[j].pose3(), m) > 1e-12) continue;
      here = true;
      EXPECT_EQ(j == 0, c.expected_entry >= team.truth[owner].size());  // odometry first while moving
      EXPECT_TRUE(factors[j].covarianceMatrix().isApprox(kLcCov, 0.0));
      EXPECT_TRUE(ds.potential_outliers->at(owner).count({c.expected_entry, j}));
    }
    EXPECT_TRUE(here) << jrl::keyName(k1) << "->" << jrl::keyName(k2) << " not in entry " << c.expected_entry;
    found += here;
  }
  EXPECT_EQ(found, team.closures.size());
  // After b's last keyframe: one closure per entry, stamped computed_at (+1 ns for the tie).
  const auto& b = ds.measurements.at('b');
  ASSERT_EQ(b.size(), 33u);
  const StampNs last = team.stamps['b'].back();
  EXPECT_EQ(b[30].stamp, last + 2000000000ULL);
  EXPECT_EQ(b[31].stamp, last + 2000000001ULL);
  EXPECT_EQ(b[32].stamp, last + 5000000000ULL);
  for (std::size_t e = 30; e < 33; ++e) EXPECT_EQ(b[e].factors.size(), 1u);
  // Within an entry: computed_at order (a30: the closure at the keyframe stamp, then the one 10 ns later,
  // both a30 -> a5).
  const auto& a30 = ds.measurements.at('a')[30].factors;
  ASSERT_EQ(a30.size(), 3u);
  for (const auto& c : team.closures) {
    if (c.lc.key1 == symbol('a', 30) && c.lc.key2 == symbol('a', 5)) {
      EXPECT_LT(poseDistance(a30[1].pose3(), c.lc.measurement), 1e-12);
    }
    if (c.lc.key1 == symbol('a', 5) && c.lc.key2 == symbol('a', 30)) {
      EXPECT_LT(poseDistance(a30[2].pose3(), c.lc.measurement.inverse(Eigen::Isometry)), 1e-12);
    }
  }
  EXPECT_EQ(report.intra, 8u);
  EXPECT_EQ(report.inter, 14u);
  EXPECT_EQ(report.odometry, 39u + 29u);
  EXPECT_TRUE(report.labelled);
}

TEST_F(RecorderTest, PotentialOutliersAreEveryLoopClosureAndLabelsFollowTheRule) {
  std::size_t potential = 0, outliers = 0;
  for (const char r : ds.robots) {
    const auto& entries = ds.measurements.at(r);
    const auto& pot = ds.potential_outliers->at(r);
    const auto& out = ds.outliers->at(r);
    for (std::size_t e = 0; e < entries.size(); ++e) {
      for (std::size_t j = 0; j < entries[e].factors.size(); ++j) {
        const jrl::Factor& f = entries[e].factors[j];
        const bool odometry = f.isPriorPose3() || (j == 0 && e < team.truth[r].size());
        EXPECT_EQ(pot.count({e, j}), odometry ? 0u : 1u) << r << " " << e << "," << j;
        if (odometry) continue;
        const Pose3 truth = jrl::pose3At(ds.groundtruth->at(r), f.keys[0]).inverse(Eigen::Isometry) *
                            jrl::pose3At(ds.groundtruth->at(r), f.keys[1]);
        const double d2 = dataset::chi2Distance(f.pose3(), truth, f.covarianceMatrix());
        EXPECT_EQ(out.count({e, j}) == 1, std::sqrt(d2) > dataset::kChi2Critical95Dof6) << r << " " << e << "," << j;
      }
    }
    for (const auto& id : out) EXPECT_TRUE(pot.count(id));
    potential += pot.size();
    outliers += out.size();
  }
  EXPECT_EQ(potential, team.closures.size());
  std::size_t injected = 0;
  for (const auto& c : team.closures) injected += c.injected_outlier;
  EXPECT_EQ(outliers, injected);  // gross errors are caught, N(0, Q) noise never reaches d = 12.6
  EXPECT_EQ(report.outliers, injected);
}

TEST_F(RecorderTest, KeySetsAndInitialization) {
  for (const char r : ds.robots) {
    std::set<jrl::Key> referenced;
    for (const auto& e : ds.measurements.at(r))
      for (const auto& f : e.factors) referenced.insert(f.keys.begin(), f.keys.end());
    std::set<jrl::Key> gt_keys, init_keys;
    for (const auto& [k, v] : ds.groundtruth->at(r)) gt_keys.insert(k);
    for (const auto& [k, v] : ds.initialization->at(r)) init_keys.insert(k);
    EXPECT_EQ(gt_keys, referenced) << r;
    EXPECT_EQ(init_keys, referenced) << r;
    // Ground truth = reference poses (teammates' keys included).
    for (const jrl::Key k : referenced)
      EXPECT_LT(poseDistance(jrl::pose3At(ds.groundtruth->at(r), k), team.truth[jrl::robotOf(k)][jrl::indexOf(k)]),
                1e-12);
    // Dead reckoning from the prior.
    Pose3 dr = team.truth[r][0];
    for (const auto& k : team.keyframes) {
      if (k.robot != r) continue;
      if (k.index > 0) dr = dr * k.odometry;
      EXPECT_LT(poseDistance(jrl::pose3At(ds.initialization->at(r), symbol(r, k.index)), dr), 1e-9);
    }
  }
  // b's a7 comes from the first closure that refers to it (b8 -> a7), not the second (b9 -> a7).
  const auto& init_b = ds.initialization->at('b');
  const jrl::Factor& first = ds.measurements.at('b')[8].factors.at(1);
  ASSERT_EQ(first.keys, (std::vector<jrl::Key>{symbol('b', 8), symbol('a', 7)}));
  EXPECT_LT(poseDistance(jrl::pose3At(init_b, symbol('a', 7)), jrl::pose3At(init_b, symbol('b', 8)) * first.pose3()),
            1e-9);
  const jrl::Factor& second = ds.measurements.at('b')[9].factors.at(1);
  EXPECT_GT(poseDistance(jrl::pose3At(init_b, symbol('a', 7)), jrl::pose3At(init_b, symbol('b', 9)) * second.pose3()),
            1e-6);
  // And it differs from a's own dead-reckoned estimate of a7.
  EXPECT_GT(
      poseDistance(jrl::pose3At(init_b, symbol('a', 7)), jrl::pose3At(ds.initialization->at('a'), symbol('a', 7))),
      1e-6);
}

TEST_F(RecorderTest, DeterministicWhateverTheArrivalOrder) {
  const std::string bytes = jrl::dumpJrl(ds);
  auto shuffled = team;
  std::mt19937_64 rng(3);
  std::shuffle(shuffled.keyframes.begin(), shuffled.keyframes.end(), rng);
  std::shuffle(shuffled.closures.begin(), shuffled.closures.end(), rng);
  dataset::DatasetRecorder other("synthetic_team", {'a', 'b'}, models());
  test::feed(other, shuffled);
  EXPECT_EQ(jrl::dumpJrl(other.build()), bytes);
  EXPECT_EQ(jrl::dumpJrl(rec.build()), bytes);  // build() does not change the recorder
}

TEST_F(RecorderTest, WritesAtomicallyAndParsesBack) {
  const auto dir = std::filesystem::temp_directory_path() / ("cosmo_recorder_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "synthetic_team.jrl").string();
  const dataset::BuildReport written = rec.write(path);
  EXPECT_TRUE(written.labelled);
  const jrl::Dataset back = jrl::readJrl(path);
  EXPECT_EQ(jrl::dumpJrl(back), jrl::dumpJrl(ds));
  const std::string meta = readWholeFileOrEmpty(dataset::DatasetRecorder::metadataPath(path));
  EXPECT_NE(meta.find("outlier_labels: true"), std::string::npos);
  EXPECT_NE(meta.find("outlier_rule: fidelity"), std::string::npos);
  const YAML::Node yaml = YAML::LoadFile(dataset::DatasetRecorder::metadataPath(path));
  EXPECT_TRUE(yaml["outlier_labels"].as<bool>());
  EXPECT_EQ(yaml["outliers"].as<std::size_t>(), written.outliers);
  EXPECT_EQ(yaml["name"].as<std::string>(), "synthetic_team");
  const std::string stats = readWholeFileOrEmpty(dataset::DatasetRecorder::statsPath(path));
  EXPECT_EQ(dataset::DatasetRecorder::statsPath(path), (dir / "synthetic_team.stats.txt").string());
  // The stats table, then the noise models the labels were made with (file and provenance).
  EXPECT_EQ(stats, jrl::formatStats(jrl::computeStats(ds)) + "\nnoise models: (built in code) (test)\n");
  EXPECT_EQ(yaml["noise_models"]["environment"].as<std::string>(), "test");
  EXPECT_EQ(yaml["noise_models"]["file"].as<std::string>(), "(built in code)");
  for (const auto& f : std::filesystem::directory_iterator(dir))  // no temporary files left behind
    EXPECT_EQ(f.path().string().find(".tmp."), std::string::npos) << f.path();
  // A failing write (missing folder) throws and leaves the previous file untouched.
  EXPECT_THROW(rec.write((dir / "missing" / "x.jrl").string()), std::exception);
  std::filesystem::remove_all(dir);
}

TEST_F(RecorderTest, SquaredRuleLabelsMore) {
  dataset::DatasetRecorder squared("synthetic_team", {'a', 'b'}, models(), dataset::OutlierRule::Squared);
  test::feed(squared, team);
  dataset::BuildReport r;
  const jrl::Dataset d = squared.build(&r);
  EXPECT_GE(r.outliers, report.outliers);
  for (const char robot : d.robots)
    for (const auto& id : ds.outliers->at(robot)) EXPECT_TRUE(d.outliers->at(robot).count(id));
  EXPECT_NE(squared.metadataYaml(r).find("outlier_rule: squared"), std::string::npos);
}

TEST(Recorder, WithoutReferencePosesNoLabels) {
  const auto team = test::makeTeam(kOdoCov, kLcCov, 7);
  dataset::DatasetRecorder rec("no_reference", {'a', 'b'}, models());
  test::feed(rec, team, false);
  dataset::BuildReport report;
  const jrl::Dataset ds = rec.build(&report);
  EXPECT_FALSE(report.labelled);
  EXPECT_FALSE(ds.groundtruth.has_value());
  EXPECT_FALSE(ds.outliers.has_value());
  ASSERT_TRUE(ds.potential_outliers.has_value());
  EXPECT_EQ(ds.potential_outliers->at('a').size() + ds.potential_outliers->at('b').size(), team.closures.size());
  EXPECT_TRUE(ds.measurements.at('a')[0].factors[0].pose3().isApprox(Pose3::Identity()));
  EXPECT_NE(rec.metadataYaml(report).find("outlier_labels: false"), std::string::npos);
  const jrl::Dataset back = jrl::parseJrl(jrl::dumpJrl(ds));
  EXPECT_FALSE(back.outliers.has_value());
}

TEST(Recorder, GapsAndDanglingClosuresWaitForTheirKeyframes) {
  const auto team = test::makeTeam(kOdoCov, kLcCov, 7);
  dataset::DatasetRecorder rec("gap", {'a', 'b', 'c'}, models());
  const test::SyntheticKeyframe* held = nullptr;
  for (const auto& k : team.keyframes) {
    if (k.robot == 'b' && k.index == 10) {
      held = &k;
      continue;
    }
    rec.addKeyframe(k.robot, k.index, k.stamp, k.odometry, k.truth);
  }
  for (const auto& c : team.closures) rec.addLoopClosure(c.lc);
  dataset::BuildReport report;
  jrl::Dataset ds = rec.build(&report);
  EXPECT_EQ(ds.robots, (std::vector<char>{'a', 'b'}));  // c never sent anything
  EXPECT_EQ(report.robots_without_keyframes, std::vector<char>{'c'});
  EXPECT_EQ(ds.measurements.at('b').size(), 10u);  // b0..b9, nothing after the gap
  EXPECT_EQ(report.keyframes_pending, 19u);
  EXPECT_GT(report.loop_closures_pending, 0u);
  EXPECT_NO_THROW(jrl::parseJrl(jrl::dumpJrl(ds)));
  // The late keyframe arrives: everything is there.
  rec.addKeyframe(held->robot, held->index, held->stamp, held->odometry, held->truth);
  ds = rec.build(&report);
  EXPECT_EQ(report.keyframes_pending, 0u);
  EXPECT_EQ(report.loop_closures_pending, 0u);
  EXPECT_EQ(ds.measurements.at('b').size(), 33u);
  EXPECT_TRUE(jrl::validate(ds).empty());
}

TEST(Recorder, RefusesBadInputWithoutLosingState) {
  dataset::DatasetRecorder rec("bad", {'a', 'b'}, models());
  const Pose3 step = makePose(1, 0, 0, 0, 0, 0);
  rec.addKeyframe('a', 0, 100, Pose3::Identity(), Pose3::Identity());
  rec.addKeyframe('a', 1, 200, step, step);
  EXPECT_THROW(rec.addKeyframe('z', 0, 100, step, std::nullopt), std::invalid_argument);
  EXPECT_THROW(rec.addKeyframe('a', 1, 300, step, std::nullopt), std::invalid_argument);  // duplicate
  EXPECT_THROW(rec.addKeyframe('a', 2, 150, step, std::nullopt), std::invalid_argument);  // stamp goes back
  Pose3 nan = step;
  nan.translation().x() = std::nan("");
  EXPECT_THROW(rec.addKeyframe('a', 2, 300, nan, std::nullopt), std::invalid_argument);
  rec.addKeyframe('a', 2, 300, step, nan);  // a NaN reference is "no reference"
  dataset::LoopClosureMeasurement lc{'b', 250, symbol('a', 2), symbol('a', 0), step};
  EXPECT_THROW(rec.addLoopClosure(lc), std::invalid_argument);  // owner b owns neither key
  lc.owner = 'a';
  lc.key2 = lc.key1;
  EXPECT_THROW(rec.addLoopClosure(lc), std::invalid_argument);
  lc.key2 = symbol('a', 0);
  rec.addLoopClosure(lc);
  EXPECT_THROW(rec.addLoopClosure(lc), std::invalid_argument);  // the same closure twice
  EXPECT_EQ(rec.counts().rejected, 7u);
  EXPECT_EQ(rec.counts().keyframes.at('a'), 3u);
  EXPECT_EQ(rec.counts().loop_closures, 1u);
  dataset::BuildReport report;
  const jrl::Dataset ds = rec.build(&report);
  EXPECT_FALSE(report.labelled);  // a2 has no usable reference
  EXPECT_EQ(ds.robots, std::vector<char>{'a'});
  EXPECT_EQ(ds.measurements.at('a').size(), 3u);
  EXPECT_NE(rec.progressLine().find("keyframes a 3 b 0"), std::string::npos) << rec.progressLine();
}

TEST(Recorder, EmptyRecorderBuilds) {
  dataset::DatasetRecorder rec("empty", {'a'}, dataset::NoiseModels{});
  dataset::BuildReport report;
  const jrl::Dataset ds = rec.build(&report);
  EXPECT_TRUE(ds.robots.empty());
  EXPECT_NO_THROW(jrl::dumpJrl(ds));
}
