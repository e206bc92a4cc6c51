// radixSortByKey against std::sort on (key, payload) pairs given in payload order: packed voxel keys (a few
// varying bits per axis, duplicates), full-width random keys, and the trivial sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cosmo/common/voxel_key.hpp"
#include "cosmo/common/radix_sort.hpp"

using namespace cosmo;

namespace {
using Keyed = std::vector<std::pair<std::uint64_t, std::uint32_t>>;
void expectSameAsStdSort(Keyed v) {
  Keyed want = v;
  std::sort(want.begin(), want.end());
  radixSortByKey(v);
  EXPECT_EQ(v, want);
}
}  // namespace

TEST(RadixSort, PackedVoxelKeysWithDuplicates) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-80.0, 80.0), h(-3.0, 20.0);
  Keyed v;
  for (std::uint32_t i = 0; i < 20000; ++i)
    v.emplace_back(packVoxelKey(voxelCoord(u(rng), 1 / 1.5), voxelCoord(u(rng), 1 / 1.5), voxelCoord(h(rng), 1 / 1.5)),
                   i);
  expectSameAsStdSort(v);
}

TEST(RadixSort, FullWidthKeys) {
  std::mt19937_64 rng(5);
  Keyed v;
  for (std::uint32_t i = 0; i < 5000; ++i) v.emplace_back(rng(), i);
  v.emplace_back(~std::uint64_t{0}, 5000);
  v.emplace_back(0, 5001);
  expectSameAsStdSort(v);
}

TEST(RadixSort, TrivialSizesAndEqualKeys) {
  expectSameAsStdSort({});
  expectSameAsStdSort({{7, 0}});
  expectSameAsStdSort({{7, 0}, {7, 1}, {7, 2}});
  expectSameAsStdSort({{9, 0}, {7, 1}, {9, 2}, {7, 3}});
}
