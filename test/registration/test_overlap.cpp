// overlapFractions (all points and flagged points in one pass) against two overlapFraction calls: the same
// values, on a seeded random cloud pair with a transform and about half the points flagged.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "cosmo/registration/icp_refinement.hpp"

using namespace cosmo;

TEST(Overlap, OnePassEqualsTwoCalls) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-10.f, 10.f);
  std::vector<Eigen::Vector3f> target, source, flagged_points;
  for (int i = 0; i < 3000; ++i) target.emplace_back(u(rng), u(rng), 0.2f * u(rng));
  std::vector<unsigned char> flags;
  for (int i = 0; i < 2000; ++i) {
    source.emplace_back(u(rng), u(rng), 0.2f * u(rng));
    flags.push_back(static_cast<unsigned char>(rng() % 2));
    if (flags.back()) flagged_points.push_back(source.back());
  }
  const KdTree<3> tree(target.front().data(), target.size());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.4, -0.2, 0.1);
  for (const double d : {0.3, 0.9}) {
    const registration::Overlaps o = registration::overlapFractions(source, flags, tree, T, d);
    EXPECT_EQ(o.all, registration::overlapFraction(source, tree, T, d));
    EXPECT_EQ(o.flagged, registration::overlapFraction(flagged_points, tree, T, d));
    EXPECT_GT(o.all, 0.0);
    EXPECT_LT(o.all, 1.0);
  }
  const registration::Overlaps none =
      registration::overlapFractions(source, std::vector<unsigned char>(source.size(), 0), tree, T, 0.9);
  EXPECT_EQ(none.flagged, 0.0);
}
