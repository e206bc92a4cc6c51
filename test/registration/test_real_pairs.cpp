// Global registration on real scan pairs from ../shared/data/scan_snippets (skipped without it), including a
// 180 deg yaw of the source, plus determinism and degenerate input.
#include <gtest/gtest.h>

#include "cosmo/common/scan_io.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/registration/global_registration.hpp"
#include "cosmo/bench/snippet_pairs.hpp"
#include "cosmo/registration/pair_evaluation.hpp"

using namespace cosmo;

namespace {
void expectRegistered(const registration::ScanPair& p, double yaw_deg) {
  const registration::GlobalRegistration reg;
  const double yaw = yaw_deg * M_PI / 180.0;
  const Scan src = registration::rotateScanYaw(readScanFile(p.source), yaw);
  const Scan tgt = readScanFile(p.target);
  const registration::RegistrationResult r = reg.align(src, tgt);
  const Pose3 expected = p.T_target_source * Pose3(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())).inverse();
  const registration::PoseError e = registration::poseError(r.T_target_source, expected);
  EXPECT_TRUE(r.valid) << p.name << ": " << r.reason;
  EXPECT_LE(e.translation_m, 0.3) << p.name << " yaw " << yaw_deg;
  EXPECT_LE(e.rotation_deg, 1.0) << p.name << " yaw " << yaw_deg;
  EXPECT_GE(r.final_inliers, 20u) << p.name;
}
std::optional<std::vector<registration::ScanPair>> pairs() {
  const auto root = sharedPath("data/scan_snippets");
  if (!root) return std::nullopt;
  return bench::snippetPairs(*root, false);
}
const registration::ScanPair& named(const std::vector<registration::ScanPair>& all, const std::string& name) {
  for (const auto& p : all)
    if (p.name == name) return p;
  throw std::runtime_error("no pair " + name);
}
}  // namespace

TEST(RealPairs, Kitti94To95Rotated180) {
  const auto all = pairs();
  if (!all) GTEST_SKIP() << "../shared/data/scan_snippets not found (set COSMO_SHARED_DIR)";
  expectRegistered(named(*all, "kitti00_94-95"), 180.0);
}

TEST(RealPairs, Hdl32Rotated90) {
  const auto all = pairs();
  if (!all) GTEST_SKIP() << "../shared/data/scan_snippets not found (set COSMO_SHARED_DIR)";
  expectRegistered(named(*all, "hdl32"), 90.0);
}

TEST(RealPairs, MulranKaist03Consecutive) {
  const auto all = pairs();
  if (!all) GTEST_SKIP() << "../shared/data/scan_snippets not found (set COSMO_SHARED_DIR)";
  expectRegistered(named(*all, "kaist03_0-1"), 0.0);
}

TEST(RealPairs, GateRejectsDifferentPlaces) {
  // KITTI 00 frames 0 and 198 are hundreds of metres apart: no overlap, the gate must say no.
  const auto root = sharedPath("data/scan_snippets/kitti00/velodyne");
  if (!root) GTEST_SKIP() << "../shared/data/scan_snippets not found (set COSMO_SHARED_DIR)";
  const registration::GlobalRegistration reg;
  const registration::RegistrationResult r =
      reg.align(readScanFile(*root + "/000000.bin"), readScanFile(*root + "/000198.bin"));
  EXPECT_FALSE(r.valid) << "final inliers " << r.final_inliers << ", overlap " << r.overlap;
  EXPECT_LT(r.overlap, 0.7);
}

TEST(RealPairs, DeterministicResult) {
  const auto all = pairs();
  if (!all) GTEST_SKIP() << "../shared/data/scan_snippets not found (set COSMO_SHARED_DIR)";
  const registration::ScanPair& p = named(*all, "hdl32");
  const Scan src = readScanFile(p.source), tgt = readScanFile(p.target);
  const registration::GlobalRegistration reg;
  const auto a = reg.align(src, tgt), b = reg.align(src, tgt);
  EXPECT_EQ(a.T_target_source.matrix(), b.T_target_source.matrix());
  EXPECT_EQ(a.final_inliers, b.final_inliers);
  EXPECT_EQ(a.correspondences, b.correspondences);
}

TEST(GlobalRegistration, DegenerateScansAreRejectedNotCrashing) {
  const registration::GlobalRegistration reg;
  Scan empty, tiny, nan;
  tiny.points = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  nan.points.assign(100, Eigen::Vector3f(std::nanf(""), 0.f, 0.f));
  for (const Scan* s : {&empty, &tiny, &nan}) {
    const registration::RegistrationResult r = reg.align(*s, tiny);
    EXPECT_FALSE(r.valid);
    EXPECT_FALSE(r.reason.empty());
    EXPECT_TRUE(r.T_target_source.matrix().allFinite());
  }
}

TEST(RegistrationParams, ConfigFileLoadsAndRejectsBadValues) {
  const registration::RegistrationParams p = registration::RegistrationParams::fromConfig(
      ConfigNode::load(std::string(COSMO_SOURCE_DIR) + "/config/registration.yaml"));
  EXPECT_DOUBLE_EQ(p.voxel_size, 0.3);
  EXPECT_EQ(p.max_correspondences, 5000u);
  ConfigNode bad{YAML::Load("registration: {voxel_size: -1}"), "bad.yaml: "};
  EXPECT_THROW(registration::RegistrationParams::fromConfig(bad), std::runtime_error);
}
