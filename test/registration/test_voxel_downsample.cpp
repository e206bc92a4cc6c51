// Voxel downsampling against a std::map reference: one centroid per voxel in key order, also when most points
// fall in voxels of their own (the hash table grows) and with range limits.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "cosmo/common/voxel_grid.hpp"

using namespace cosmo;

namespace {
std::vector<Eigen::Vector3f> reference(const std::vector<Eigen::Vector3f>& pts, double voxel, double min_r,
                                       double max_r) {
  std::map<std::tuple<long, long, long>, std::pair<Eigen::Vector3d, int>> cells;
  for (const auto& p : pts) {
    const double r = p.cast<double>().norm();
    if (r * r < min_r * min_r || (max_r > 0 && r * r > max_r * max_r)) continue;
    auto& c = cells[{static_cast<long>(std::floor(p.x() / voxel)), static_cast<long>(std::floor(p.y() / voxel)),
                     static_cast<long>(std::floor(p.z() / voxel))}];
    if (c.second == 0) c.first.setZero();
    c.first += p.cast<double>();
    ++c.second;
  }
  std::vector<Eigen::Vector3f> out;
  for (const auto& [key, c] : cells) out.push_back((c.first / c.second).cast<float>());
  return out;
}
}  // namespace

TEST(VoxelDownsample, MatchesReference) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> wide(-40.f, 40.f), local(-0.5f, 0.5f);
  std::vector<Eigen::Vector3f> pts;
  for (int k = 0; k < 3000; ++k) pts.emplace_back(wide(rng), wide(rng), 0.1f * wide(rng));    // mostly own voxels
  for (int k = 0; k < 3000; ++k) pts.emplace_back(local(rng), local(rng) + 3.f, local(rng));  // dense
  for (const auto& [min_r, max_r] : {std::pair{0.0, 0.0}, std::pair{1.0, 30.0}}) {
    const auto got = voxelDownsample(pts, 0.3, min_r, max_r);
    const auto want = reference(pts, 0.3, min_r, max_r);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT((got[i] - want[i]).norm(), 1e-5f) << i;
  }
}
