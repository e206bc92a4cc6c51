// Injected outliers (dataset/outlier_injection.hpp, outlier_kinds.hpp): the measured rate, the labels, where the
// closures go, the kinds' rules, and what a back-end sees (the inliers' solve unchanged, the robust one degrading).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cosmo/backend/pose_graph_solver.hpp"
#include "cosmo/common/shared_data.hpp"
#include "cosmo/dataset/outlier_injection.hpp"
#include "cosmo/jrl/closure_error.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/synthetic.hpp"
#include "cosmo/jrl/trajectory_error.hpp"
#include "cosmo/jrl/validate.hpp"

using namespace cosmo;

namespace {

jrl::Dataset smallTeam(std::size_t poses = 160, double natural_outliers = 0.1) {
  jrl::SyntheticParams p;
  p.poses_per_robot = poses;
  p.outlier_ratio = natural_outliers;
  std::mt19937_64 rng(7);
  return jrl::makeSyntheticDataset(p, rng);
}

struct LoopCounts {
  std::size_t intra = 0, inter = 0, intra_outliers = 0, inter_outliers = 0;
};

LoopCounts countLoops(const jrl::Dataset& d) {
  LoopCounts c;
  for (const jrl::PoseFactor& f : jrl::poseGraph(d).factors) {
    if (!f.isLoopClosure()) continue;
    const bool inter = f.kind == jrl::FactorKind::InterRobotLoopClosure;
    ++(inter ? c.inter : c.intra);
    if (f.outlier) ++(inter ? c.inter_outliers : c.intra_outliers);
  }
  return c;
}

/// The graph's factors by robot and FactorId.
std::map<std::pair<char, jrl::FactorId>, const jrl::PoseFactor*> byId(const jrl::PoseGraph& g) {
  std::map<std::pair<char, jrl::FactorId>, const jrl::PoseFactor*> out;
  for (const jrl::PoseFactor& f : g.factors) out[{f.robot, f.id}] = &f;
  return out;
}

dataset::InjectionParams params(dataset::OutlierKind kind, double rate, dataset::ClosureScope scope = dataset::ClosureScope::Both) {
  dataset::InjectionParams p;
  p.kind = kind;
  p.rate = rate;
  p.scope = scope;
  p.seed = 11;
  p.draw.group_size = 4;
  return p;
}

double robustAte(const jrl::Dataset& d) {
  const jrl::PoseGraph g = jrl::poseGraph(d);
  backend::SolverOptions o;
  o.selection = backend::FactorSelection::AllRobust;
  const backend::SolveResult r = backend::solvePoseGraph(g, o);
  return jrl::trajectoryError(g.robots, r.poses, g.groundtruth).overall.trans_m;
}

}  // namespace

TEST(OutlierInjection, MeasuredRateWithinOneClosureEveryFactorLabelledAndWrong) {
  const jrl::Dataset in = smallTeam();
  const LoopCounts before = countLoops(in);
  const std::size_t n0 = before.intra + before.inter;
  ASSERT_GT(n0, 50u);
  for (dataset::OutlierKind kind : {dataset::OutlierKind::Random, dataset::OutlierKind::Local, dataset::OutlierKind::Group, dataset::OutlierKind::Mixed})
    for (double rate : {0.05, 0.2, 0.5}) {
      SCOPED_TRACE(std::string(outlierKindName(kind)) + " " + std::to_string(rate));
      dataset::InjectionReport report;
      const jrl::Dataset out = injectOutliers(in, params(kind, rate), &report);
      const LoopCounts after = countLoops(out);
      const std::size_t n = after.intra + after.inter;
      const std::size_t injected =
          after.intra_outliers + after.inter_outliers - before.intra_outliers - before.inter_outliers;
      EXPECT_EQ(injected, report.injected);
      EXPECT_EQ(n, n0 + injected);
      EXPECT_LE(std::abs(static_cast<double>(injected) - rate * static_cast<double>(n)), 1.0);
      EXPECT_TRUE(jrl::validate(out).empty()) << jrl::validate(out).front().str();

      const jrl::PoseGraph g = jrl::poseGraph(out);
      const auto factors = byId(g);
      ASSERT_EQ(report.ids.size(), injected);
      for (const auto& [robot, id] : report.ids) {
        EXPECT_TRUE(out.potential_outliers->at(robot).count(id));
        EXPECT_TRUE(out.outliers->at(robot).count(id));
        const jrl::PoseFactor& f = *factors.at({robot, id});
        EXPECT_TRUE(f.isLoopClosure());
        EXPECT_EQ(jrl::robotOf(f.key1), robot);  // stored by the owner of the newer pose, key1 its own
        EXPECT_TRUE(exceedsRule(jrl::closureError(f, g.groundtruth).d2, dataset::OutlierRule::Fidelity));
        EXPECT_EQ(f.stamp, g.stamps.at(f.key1));  // in the entry that made key1
        EXPECT_GE(f.stamp, g.stamps.at(f.key2));
      }
      // Reads back, and the same seed gives the same bytes.
      const std::string bytes = jrl::dumpJrl(out);
      EXPECT_EQ(jrl::dumpJrl(jrl::parseJrl(bytes)), bytes);
      EXPECT_EQ(jrl::dumpJrl(injectOutliers(in, params(kind, rate))), bytes);
    }
}

TEST(OutlierInjection, ScopeAndRateOfAll) {
  const jrl::Dataset in = smallTeam();
  const LoopCounts before = countLoops(in);
  dataset::InjectionReport report;
  LoopCounts after = countLoops(injectOutliers(in, params(dataset::OutlierKind::Random, 0.3, dataset::ClosureScope::Inter), &report));
  EXPECT_EQ(after.intra, before.intra);
  EXPECT_EQ(report.injected_inter, report.injected);
  EXPECT_LE(std::abs(double(report.injected) - 0.3 * double(after.inter)), 1.0);
  after = countLoops(injectOutliers(in, params(dataset::OutlierKind::Local, 0.3, dataset::ClosureScope::Intra), &report));
  EXPECT_EQ(after.inter, before.inter);
  EXPECT_EQ(report.injected_intra, report.injected);

  dataset::InjectionParams all = params(dataset::OutlierKind::Random, 0.4);
  all.rate_of = dataset::RateOf::All;
  after = countLoops(injectOutliers(in, all));
  const double share = double(after.intra_outliers + after.inter_outliers) / double(after.intra + after.inter);
  EXPECT_LE(std::abs(share - 0.4) * double(after.intra + after.inter), 1.0);
  all.rate = 0.01;  // below the natural share
  EXPECT_THROW(injectOutliers(in, all), std::invalid_argument);
  EXPECT_EQ(jrl::dumpJrl(injectOutliers(in, params(dataset::OutlierKind::Group, 0.0))), jrl::dumpJrl(in));
  EXPECT_THROW(injectOutliers(in, params(dataset::OutlierKind::Random, 1.0)), std::invalid_argument);
  EXPECT_THROW(injectedCount(-0.1, dataset::RateOf::Injected, 10, 0), std::invalid_argument);
  EXPECT_EQ(injectedCount(0.5, dataset::RateOf::Injected, 10, 3), 10u);
  EXPECT_EQ(injectedCount(0.5, dataset::RateOf::All, 10, 3), 4u);
}

TEST(OutlierInjection, KindsFollowTheirRules) {
  const jrl::Dataset in = smallTeam();
  // local: near poses, off by 1.5-3 label bounds
  dataset::InjectionReport report;
  jrl::Dataset out = injectOutliers(in, params(dataset::OutlierKind::Local, 0.3), &report);
  jrl::PoseGraph g = jrl::poseGraph(out);
  auto factors = byId(g);
  for (const auto& [robot, id] : report.ids) {
    const jrl::PoseFactor& f = *factors.at({robot, id});
    const double d = std::sqrt(jrl::closureError(f, g.groundtruth).d2);
    EXPECT_GE(d, 1.5 * dataset::kChi2Critical95Dof6 - 1e-6);
    EXPECT_LE(d, 3.0 * dataset::kChi2Critical95Dof6 + 1e-6);
    EXPECT_LE((g.groundtruth.at(f.key1).translation() - g.groundtruth.at(f.key2).translation()).norm(), 10.0);
  }
  // group: runs of 4 consecutive pose pairs that agree with each other through the true motion
  out = injectOutliers(in, params(dataset::OutlierKind::Group, 0.3), &report);
  g = jrl::poseGraph(out);
  factors = byId(g);
  EXPECT_EQ(report.injected_group, report.injected);
  EXPECT_LE(report.groups, report.injected / 4 + 1);
  std::map<std::pair<jrl::Key, jrl::Key>, Pose3> claims;  // (key1, key2) -> claimed T1^-1 T2
  for (const auto& [robot, id] : report.ids) {
    const jrl::PoseFactor& f = *factors.at({robot, id});
    claims[{f.key1, f.key2}] = f.measured;
    claims[{f.key2, f.key1}] = f.measured.inverse();
  }
  std::size_t consistent = 0;
  for (const auto& [keys, M] : claims) {
    const auto next = claims.find({keys.first + 1, keys.second + 1});
    if (next == claims.end()) continue;
    // M^-1 * A * M_next * B^-1 = I with A, B the true motions of the two sides
    const Pose3 A = g.groundtruth.at(keys.first).inverse() * g.groundtruth.at(keys.first + 1);
    const Pose3 B = g.groundtruth.at(keys.second).inverse() * g.groundtruth.at(keys.second + 1);
    const Pose3 cycle = M.inverse() * A * next->second * B.inverse();
    EXPECT_LT(logSE3(cycle).norm(), 1e-9);
    ++consistent;
  }
  EXPECT_GE(consistent, 2 * (report.injected - report.groups));  // both orientations of every link in a group
}

TEST(OutlierInjection, InliersSolveUnchanged) {
  const jrl::Dataset in = smallTeam(120);
  backend::SolverOptions inliers;
  const backend::SolveResult base = backend::solvePoseGraph(jrl::poseGraph(in), inliers);
  for (dataset::OutlierKind kind : {dataset::OutlierKind::Random, dataset::OutlierKind::Group})
    for (double rate : {0.2, 0.6}) {
      const backend::SolveResult r = backend::solvePoseGraph(jrl::poseGraph(injectOutliers(in, params(kind, rate))), inliers);
      EXPECT_EQ(r.poses.size(), base.poses.size());
      EXPECT_EQ(r.iterations, base.iterations);
      for (const auto& [key, pose] : base.poses) EXPECT_TRUE(r.poses.at(key).matrix() == pose.matrix()) << jrl::keyName(key);
    }
}

TEST(OutlierInjection, RobustSolveOfTheReferenceFileDegradesAsTheRateGrows) {
  // On the synthetic team the Cauchy kernel shrugs off even 60 % (its initialization is close to the truth and
  // the closures' errors point every way); on a released file, drifted by 25 m, it does not (docs/benchmarks.md).
  const auto path = sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not present";
  const jrl::Dataset in = jrl::readJrl(*path);
  const double natural = robustAte(in);
  std::vector<double> ate;  // groups: the hard case (random ones the kernel rejects up to ~30 %, docs/benchmarks.md)
  for (double rate : {0.1, 0.3}) ate.push_back(robustAte(injectOutliers(in, params(dataset::OutlierKind::Group, rate))));
  std::printf("group outliers: robust ATE %.2f m as released, %.2f / %.2f m at 10 / 30 %%\n", natural, ate[0], ate[1]);
  EXPECT_GT(ate[0], natural);
  EXPECT_GT(ate[1], ate[0]);
  EXPECT_GT(ate[1], 2.0 * natural);
}

TEST(OutlierInjection, RefusesWhatItCannotDo) {
  jrl::Dataset in = smallTeam(40);
  jrl::Dataset unlabelled = in;
  unlabelled.outliers.reset();
  EXPECT_THROW(injectOutliers(unlabelled, params(dataset::OutlierKind::Random, 0.2)), std::invalid_argument);
  jrl::SyntheticParams one;
  one.robots = {'a'};
  one.poses_per_robot = 60;
  std::mt19937_64 rng(3);
  EXPECT_THROW(injectOutliers(jrl::makeSyntheticDataset(one, rng), params(dataset::OutlierKind::Random, 0.2, dataset::ClosureScope::Inter)),
               std::invalid_argument);  // no inter-robot closures to count
}

TEST(OutlierInjection, ReferenceFile) {
  const auto path = sharedPath("ref/jrl/tuhh_r3_01_night_wifi.jrl");
  if (!path) GTEST_SKIP() << "../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl not present";
  const jrl::Dataset in = jrl::readJrl(*path);
  for (dataset::OutlierKind kind : {dataset::OutlierKind::Random, dataset::OutlierKind::Local, dataset::OutlierKind::Group, dataset::OutlierKind::Mixed}) {
    dataset::InjectionReport report;
    const jrl::Dataset out = injectOutliers(in, params(kind, 0.3), &report);
    EXPECT_EQ(report.closures_before, 636u);
    EXPECT_EQ(report.natural_outliers, 75u);
    EXPECT_EQ(report.injected, 273u);  // round(0.3 * 636 / 0.7)
    EXPECT_TRUE(jrl::validate(out).empty()) << outlierKindName(kind);
  }
}
