// Pruning + robust solve on synthetic correspondences with a known transform and 50 % outliers.
#include <gtest/gtest.h>

#include <random>

#include "cosmo/registration/consistency_graph.hpp"
#include "cosmo/registration/graph_pruning.hpp"
#include "cosmo/registration/pair_evaluation.hpp"
#include "cosmo/registration/robust_solver.hpp"

using namespace cosmo;

namespace {
struct Problem {
  std::vector<Eigen::Vector3f> source, target;
  std::vector<bool> inlier;
  Pose3 T;
};
Problem makeProblem(int n, double outlier_ratio, double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  std::normal_distribution<double> g(0.0, noise);
  Problem p;
  p.T = makePose(4.0, -7.5, 0.8, 0.03, -0.02, 2.3);  // a large yaw
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d s(u(rng), u(rng), 0.1 * u(rng));
    const bool in = i >= static_cast<int>(outlier_ratio * n);
    Eigen::Vector3d t = in ? Eigen::Vector3d(p.T * s) : Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
    if (in && noise > 0) t += Eigen::Vector3d(g(rng), g(rng), g(rng));
    p.source.push_back(s.cast<float>());
    p.target.push_back(t.cast<float>());
    p.inlier.push_back(in);
  }
  return p;
}
registration::RigidEstimate pruneAndSolve(const Problem& p, double noise_bound, std::vector<int>& clique) {
  const auto graph = registration::ConsistencyGraph::fromCorrespondences(p.source, p.target, 2.0 * noise_bound);
  clique = maxClique(graph, 100000).vertices;
  std::vector<Eigen::Vector3d> s, t;
  for (const int i : clique) {
    s.push_back(p.source[static_cast<std::size_t>(i)].cast<double>());
    t.push_back(p.target[static_cast<std::size_t>(i)].cast<double>());
  }
  registration::GncParams gnc;
  gnc.noise_bound = noise_bound;
  return solveRobustRigid(s, t, gnc, 20000);
}
}  // namespace

TEST(RobustSolver, ExactRecoveryWithHalfOutliers) {
  const Problem p = makeProblem(400, 0.5, 0.0, 11);
  std::vector<int> clique;
  const registration::RigidEstimate est = pruneAndSolve(p, 0.05, clique);
  ASSERT_TRUE(est.ok);
  // The clique holds every inlier and no outlier.
  int inliers_in_clique = 0;
  for (const int i : clique) inliers_in_clique += p.inlier[static_cast<std::size_t>(i)];
  EXPECT_EQ(inliers_in_clique, 200);
  EXPECT_EQ(clique.size(), 200u);
  const registration::PoseError e = registration::poseError(est.T, p.T);
  EXPECT_LT(e.translation_m, 1e-4);
  EXPECT_LT(e.rotation_deg, 1e-4);
}

TEST(RobustSolver, NoisyInliersWithHalfOutliers) {
  const Problem p = makeProblem(1000, 0.5, 0.03, 12);
  std::vector<int> clique;
  const registration::RigidEstimate est = pruneAndSolve(p, 0.15, clique);
  ASSERT_TRUE(est.ok);
  const registration::PoseError e = registration::poseError(est.T, p.T);
  EXPECT_LT(e.translation_m, 0.05);
  EXPECT_LT(e.rotation_deg, 0.2);
  EXPECT_GE(est.inliers.size(), 400u);
}

TEST(RobustSolver, GncRotationRejectsOutliersWithoutPruning) {
  // GNC-TLS alone on translation-free vectors with 40 % gross outliers.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3d> a, b;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d v(10 * g(rng), 10 * g(rng), 10 * g(rng));
    a.push_back(v);
    b.push_back(i < 80 ? Eigen::Vector3d(10 * g(rng), 10 * g(rng), 10 * g(rng)) : Eigen::Vector3d(R * v));
  }
  registration::GncParams params;
  params.noise_bound = 0.1;
  const registration::RotationEstimate est = gncTlsRotation(a, b, params);
  EXPECT_LT(Eigen::AngleAxisd(est.R.transpose() * R).angle(), 1e-6);
}

TEST(RobustSolver, TlsTranslationIgnoresOutliers) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 30; ++i) v.emplace_back(1.0 + 0.01 * (i % 3), -2.0, 0.5);
  for (int i = 0; i < 20; ++i) v.emplace_back(10.0 * i, 5.0 - i, 3.0 * i);
  const registration::TranslationEstimate t = registration::tlsTranslation(v, 0.1);
  EXPECT_NEAR(t.t.x(), 1.01, 1e-9);
  EXPECT_NEAR(t.t.y(), -2.0, 1e-9);
  EXPECT_NEAR(t.t.z(), 0.5, 1e-9);
  int inl = 0;
  for (const bool b : t.inliers) inl += b;
  EXPECT_EQ(inl, 30);
}

TEST(RobustSolver, DegenerateInputDoesNotCrash) {
  registration::GncParams params;
  EXPECT_FALSE(solveRobustRigid({}, {}, params, 100).ok);
  EXPECT_FALSE(solveRobustRigid({Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()},
                                {Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()}, params, 100)
                   .ok);
  // Identical points: a solution, no NaN.
  const std::vector<Eigen::Vector3d> same(5, Eigen::Vector3d(1, 2, 3));
  const registration::RigidEstimate e = solveRobustRigid(same, same, params, 100);
  EXPECT_TRUE(e.T.matrix().allFinite());
}
