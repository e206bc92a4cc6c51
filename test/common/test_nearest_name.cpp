// nearestName (the "did you mean" of every config reader) against a plain search over every known name with the
// full edit distance: the same answer for misspellings, unrelated keys and very long keys (its length bound only
// skips names that cannot win).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "cosmo/common/nearest_name.hpp"

namespace {

std::size_t levenshtein(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j)
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
  return d[a.size()][b.size()];
}

/// The rule without shortcuts: the first name of least distance, if that distance is below the key's length and
/// at most max(2, a third of it).
std::string plainNearest(const std::string& key, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_distance = key.size();
  for (const std::string& k : known) {
    const std::size_t d = levenshtein(key, k);
    if (d < best_distance) best = k, best_distance = d;
  }
  return best_distance <= std::max<std::size_t>(2, key.size() / 3) ? best : std::string();
}

const std::vector<std::string> kKnown{"seed",
                                      "voxel_size",
                                      "max_range",
                                      "min_plane_spread_ratio",
                                      "edge_threshold",
                                      "rings",
                                      "sectors",
                                      "threshold",
                                      "num_candidates",
                                      "exclude_recent",
                                      "rebuild_every",
                                      "a",
                                      "keyframe_distance",
                                      "gate",
                                      "gate_threshold"};

}  // namespace

TEST(NearestName, MisspellingsFindTheirName) {
  EXPECT_EQ(cosmo::nearestName("voxelsize", kKnown), "voxel_size");
  EXPECT_EQ(cosmo::nearestName("min_plane_spred_ratio", kKnown), "min_plane_spread_ratio");
  EXPECT_EQ(cosmo::nearestName("sed", kKnown), "seed");
  EXPECT_EQ(cosmo::nearestName("completely_unrelated_key", kKnown), "");
  EXPECT_EQ(cosmo::nearestName(std::string(5000, 'x'), kKnown), "");
}

TEST(NearestName, AgreesWithThePlainSearchOnRandomKeys) {
  std::mt19937_64 rng(7);
  const std::string letters = "abcdeghilmnoprstvx_";
  std::uniform_int_distribution<std::size_t> pick(0, letters.size() - 1), length(0, 40), name(0, kKnown.size() - 1),
      edits(0, 4);
  for (int i = 0; i < 3000; ++i) {
    std::string key;
    if (i % 2 == 0) {  // a known name with a few random edits
      key = kKnown[name(rng)];
      for (std::size_t e = edits(rng); e > 0; --e) {
        const std::size_t at = key.empty() ? 0 : rng() % (key.size() + 1);
        switch (rng() % 3) {
          case 0: key.insert(at, 1, letters[pick(rng)]); break;
          case 1:
            if (at < key.size()) key.erase(at, 1);
            break;
          default:
            if (at < key.size()) key[at] = letters[pick(rng)];
        }
      }
    } else {
      for (std::size_t n = length(rng); n > 0; --n) key += letters[pick(rng)];
    }
    EXPECT_EQ(cosmo::nearestName(key, kKnown), plainNearest(key, kKnown)) << "key '" << key << "'";
  }
}
