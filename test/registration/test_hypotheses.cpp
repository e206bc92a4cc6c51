// Hypothesis verification: when the maximum clique of the consistency graph is a wrong, self-consistent set of
// correspondences (a repetitive or symmetric scene), its solution overlaps the target poorly and the gate
// rejects it; the next clique, among the correspondences that solution does not explain, is solved, verified
// and reported.
#include <gtest/gtest.h>

#include <random>

#include "cosmo/registration/global_registration.hpp"
#include "cosmo/registration/pair_evaluation.hpp"

using namespace cosmo;

namespace {

struct Scene {
  registration::FeatureCloud source, target;
  Pose3 T_true, T_wrong;
};

/// Target: sparse random points (with normals) in a 60 x 60 x 10 m box; source: the same points seen from
/// T_true. Correspondences are designed through identical random feature vectors: `n_true` right ones
/// (source point -> its own target point) and `n_wrong` that all agree with T_wrong (source point -> an extra
/// target point placed at T_wrong * source point).
Scene makeScene(int n_true, int n_wrong, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-30.f, 30.f), uz(-5.f, 5.f), uf(0.f, 100.f);
  std::normal_distribution<float> g(0.f, 1.f);
  Scene s;
  s.T_true = makePose(3.0, -2.0, 0.1, 0.0, 0.0, 0.6);
  s.T_wrong = makePose(-6.0, 4.0, 0.0, 0.0, 0.0, 0.6 + M_PI);
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f t(u(rng), u(rng), uz(rng));
    const Eigen::Vector3f nt = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    s.target.points.push_back(t);
    s.target.normals.push_back(nt);
    s.source.points.push_back((s.T_true.inverse() * t.cast<double>()).cast<float>());
    s.source.normals.push_back((s.T_true.linear().transpose() * nt.cast<double>()).cast<float>());
  }
  const int k = n_true + n_wrong;
  s.source.features = registration::FpfhMatrix(registration::kFpfhDim, k);
  s.target.features = registration::FpfhMatrix(registration::kFpfhDim, k);
  for (int c = 0; c < k; ++c) {
    const int i = 7 * c + 3;  // a source point
    for (int d = 0; d < registration::kFpfhDim; ++d) s.source.features(d, c) = uf(rng);
    s.target.features.col(c) = s.source.features.col(c);
    s.source.keypoints.push_back(i);
    if (c < n_true) {
      s.target.keypoints.push_back(i);  // the same point in the target
    } else {
      const Eigen::Vector3f w = (s.T_wrong * s.source.points[static_cast<std::size_t>(i)].cast<double>()).cast<float>();
      s.target.keypoints.push_back(static_cast<int>(s.target.points.size()));
      s.target.points.push_back(w);
      s.target.normals.push_back(Eigen::Vector3f::UnitZ());
    }
  }
  return s;
}

}  // namespace

TEST(Hypotheses, WrongMaximumCliqueIsRejectedAndTheNextOneReported) {
  const Scene s = makeScene(8, 12, 5);
  registration::RegistrationParams p;
  p.max_hypotheses = 1;
  const registration::RegistrationResult first_only = registration::GlobalRegistration(p).align(s.source, s.target);
  EXPECT_FALSE(first_only.valid) << "the wrong maximum clique must fail the overlap gate";
  EXPECT_EQ(first_only.pruned_inliers, 12u);
  EXPECT_LT(first_only.overlap, 0.5);
  EXPECT_LT(registration::poseError(first_only.T_target_source, s.T_wrong).translation_m, 0.3);

  p.max_hypotheses = 3;
  const registration::RegistrationResult r = registration::GlobalRegistration(p).align(s.source, s.target);
  EXPECT_TRUE(r.valid) << r.reason;
  EXPECT_EQ(r.hypotheses, 2);
  EXPECT_EQ(r.hypothesis, 1);
  EXPECT_EQ(r.pruned_inliers, 8u);
  EXPECT_GT(r.overlap, 0.95);
  const registration::PoseError e = registration::poseError(r.T_target_source, s.T_true);
  EXPECT_LT(e.translation_m, 0.05);
  EXPECT_LT(e.rotation_deg, 0.2);
}

TEST(Hypotheses, RightMaximumCliqueNeedsOneHypothesis) {
  const Scene s = makeScene(12, 8, 9);
  const registration::RegistrationResult r = registration::GlobalRegistration().align(s.source, s.target);
  EXPECT_TRUE(r.valid) << r.reason;
  EXPECT_EQ(r.hypotheses, 1);
  EXPECT_EQ(r.hypothesis, 0);
  EXPECT_LT(registration::poseError(r.T_target_source, s.T_true).translation_m, 0.05);
}

TEST(Hypotheses, NoHypothesisPassesOnUnrelatedClouds) {
  // Only the wrong, self-consistent set of correspondences: its solution overlaps poorly, nothing is left for
  // a next hypothesis, the result stays rejected.
  Scene s = makeScene(0, 12, 13);
  const registration::RegistrationResult r = registration::GlobalRegistration().align(s.source, s.target);
  EXPECT_FALSE(r.valid);
  EXPECT_GE(r.hypotheses, 1);
}
