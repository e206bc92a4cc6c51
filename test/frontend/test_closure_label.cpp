// The label a front-end shows a loop closure with (frontend/closure_label.hpp): rejected, or accepted and an
// inlier / outlier by the chi^2 rule against the two keyframes' references, or unlabelled without them.
#include <gtest/gtest.h>

#include "cosmo/frontend/closure_label.hpp"

using namespace cosmo;
using namespace cosmo::frontend;

namespace {
Pose3 at(double x, double y, double yaw) {
  return makePose(Eigen::Vector3d(x, y, 0), Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())));
}
LoopClosureAttempt closure(const Pose3& measurement, bool accepted = true) {
  LoopClosureAttempt a;
  a.owner = a.robot1 = 'a';
  a.index1 = 7;
  a.robot2 = 'b';
  a.index2 = 3;
  a.measurement = measurement;
  a.accepted = accepted;
  return a;
}
}  // namespace

TEST(ClosureLabel, InlierAndOutlierByTheChi2RuleAgainstTheReferences) {
  ClosureLabeller labeller{dataset::NoiseModels{}};
  labeller.addReference('a', 7, at(10, 0, 0.1));
  labeller.addReference('b', 3, at(12, 1, 0.3));
  const Pose3 truth = at(10, 0, 0.1).inverse() * at(12, 1, 0.3);
  EXPECT_EQ(labeller.label(closure(truth)), ClosureLabel::Inlier);
  EXPECT_EQ(labeller.label(closure(truth * at(5.0, 0, 0.5))), ClosureLabel::Outlier);
  EXPECT_EQ(labeller.label(closure(truth, false)), ClosureLabel::Rejected);
}

TEST(ClosureLabel, UnlabelledWithoutAReferenceOrNoiseModels) {
  ClosureLabeller labeller{dataset::NoiseModels{}};
  labeller.addReference('a', 7, at(10, 0, 0.1));
  EXPECT_EQ(labeller.label(closure(Pose3::Identity())), ClosureLabel::Unlabelled);  // b3 has none
  ClosureLabeller without{std::nullopt};
  without.addReference('a', 7, at(10, 0, 0.1));
  without.addReference('b', 3, at(12, 1, 0.3));
  EXPECT_EQ(without.label(closure(Pose3::Identity())), ClosureLabel::Unlabelled);
  EXPECT_EQ(without.label(closure(Pose3::Identity(), false)), ClosureLabel::Rejected);
}
