// The odometry factor across a front-end's restart (dataset/gap_bridge.hpp) and the DatasetRecorder's chains with
// bridges: one connected trajectory per robot, the bridge listed in the metadata, across a hole in the indices.
#include <gtest/gtest.h>

#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/gap_bridge.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"

using namespace cosmo;
using namespace cosmo::dataset;

namespace {

Matrix6 odometryCovariance() {
  Matrix6 c = Matrix6::Zero();
  c.diagonal() << 1e-4, 1e-4, 1e-4, 1e-3, 1e-3, 1e-3;
  return c;
}

NoiseModels models() {
  NoiseModels m;
  m.odometry = odometryCovariance();
  m.loop_closure = odometryCovariance() * 4;
  m.environment = "test";
  return m;
}

constexpr StampNs kT0 = 1700000000000000000ULL;
constexpr StampNs kSecond = 1000000000ULL;

Pose3 truth(std::size_t i) { return makePose(2.0 * i, 0.1 * i, 0.0, 0.0, 0.0, 0.05 * i); }

}  // namespace

TEST(GapBridge, WithReferencesTheRelativePoseAndTheCovarianceOfTheStepsItSpans) {
  const Pose3 before = makePose(10, 0, 0, 0, 0, 0.3), after = makePose(10, 7, 0, 0, 0, 1.2);
  const GapBridge b = bridgeGap(kT0, before, kT0 + 12 * kSecond, after, odometryCovariance(), 2.0);
  EXPECT_EQ(b.rule, "reference");
  EXPECT_DOUBLE_EQ(b.gap_seconds, 12.0);
  EXPECT_TRUE((b.measurement.matrix() - (before.inverse(Eigen::Isometry) * after).matrix()).isZero(1e-12));
  EXPECT_DOUBLE_EQ(b.steps, 3.5);  // 7 m at 2 m per keyframe
  EXPECT_TRUE((b.covariance - 3.5 * odometryCovariance()).isZero(1e-15));
  // a robot that stood still: one step
  const GapBridge still = bridgeGap(kT0, before, kT0 + 60 * kSecond, before, odometryCovariance(), 2.0);
  EXPECT_DOUBLE_EQ(still.steps, 1.0);
  EXPECT_TRUE((still.covariance - odometryCovariance()).isZero(1e-15));
}

TEST(GapBridge, WithoutAReferenceTheFactorSaysNothing) {
  const GapBridge b = bridgeGap(kT0, std::nullopt, kT0 + kSecond, makePose(1, 2, 3, 0, 0, 0), odometryCovariance());
  EXPECT_EQ(b.rule, "unknown");
  EXPECT_TRUE(b.measurement.matrix().isIdentity());
  EXPECT_TRUE((b.covariance - unknownBridgeCovariance()).isZero());
  EXPECT_GT(b.covariance(3, 3), 1e5);
}

TEST(GapBridge, TheRecorderJoinsARestartedFrontendsKeyframesToTheTrajectory) {
  DatasetRecorder rec("bridged", {'a'}, models());
  for (std::size_t i = 0; i < 5; ++i)
    rec.addKeyframe('a', i, kT0 + i * kSecond, i ? truth(i - 1).inverse(Eigen::Isometry) * truth(i) : Pose3::Identity(),
                    truth(i));
  // keyframe 5 reached a teammate but not the recorder; the restarted front-end goes on at 6, bridged from 4
  rec.addKeyframe('a', 6, kT0 + 9 * kSecond, Pose3::Identity(), truth(6), 4);
  rec.addKeyframe('a', 7, kT0 + 10 * kSecond, truth(6).inverse(Eigen::Isometry) * truth(7), truth(7));
  EXPECT_EQ(rec.chainEnd('a'), std::optional<std::size_t>(7));
  BuildReport report;
  const jrl::Dataset ds = rec.build(&report);
  EXPECT_EQ(report.keyframes_pending, 0u);
  ASSERT_EQ(report.bridges.size(), 1u);
  EXPECT_EQ(report.bridges[0].from, 4u);
  EXPECT_EQ(report.bridges[0].to, 6u);
  EXPECT_DOUBLE_EQ(report.bridges[0].gap_seconds, 5.0);
  EXPECT_EQ(report.bridges[0].rule, "reference");
  const auto& entries = ds.measurements.at('a');
  ASSERT_EQ(entries.size(), 7u);
  const jrl::Factor& bridge = entries[5].factors[0];
  EXPECT_EQ(bridge.keys[0], jrl::symbol('a', 4));
  EXPECT_EQ(bridge.keys[1], jrl::symbol('a', 6));
  const GapBridge expected = bridgeGap(kT0 + 4 * kSecond, truth(4), kT0 + 9 * kSecond, truth(6), odometryCovariance());
  EXPECT_TRUE((bridge.covarianceMatrix() - expected.covariance).isZero(1e-12));
  for (const auto& v : jrl::validate(ds)) ADD_FAILURE() << v.str();
  // the metadata lists it
  const std::string yaml = rec.metadataYaml(report);
  EXPECT_NE(yaml.find("bridges:\n  - {robot: a, from: a4, to: a6, gap_seconds: 5, rule: reference}"), std::string::npos)
      << yaml;
}

TEST(GapBridge, AChainWithoutBridgesIsUnchanged) {
  DatasetRecorder rec("plain", {'a'}, models());
  for (std::size_t i = 0; i < 4; ++i) rec.addKeyframe('a', i, kT0 + i * kSecond, Pose3::Identity(), truth(i));
  rec.addKeyframe('a', 6, kT0 + 9 * kSecond, Pose3::Identity(), truth(6));  // after a gap, not bridged: pending
  BuildReport report;
  rec.build(&report);
  EXPECT_EQ(report.keyframes_pending, 1u);
  EXPECT_TRUE(report.bridges.empty());
  EXPECT_NE(rec.metadataYaml(report).find("bridges: []\n"), std::string::npos);
  EXPECT_EQ(rec.chainEnd('a'), std::optional<std::size_t>(3));
  EXPECT_THROW(rec.addKeyframe('a', 7, kT0 + 10 * kSecond, Pose3::Identity(), truth(7), 7), std::invalid_argument);
}
