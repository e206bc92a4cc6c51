// The reference poses a player sends beside the scans (sequence/reference_stream.hpp): the reference's stamps
// since the previous scan, thinned to the spacing, then the scan's stamp.
#include <gtest/gtest.h>

#include "cosmo/sequence/reference_stream.hpp"

using namespace cosmo;
using namespace cosmo::sequence;

namespace {
constexpr StampNs kMs = 1000000ULL;
Trajectory every10ms(StampNs from, StampNs to) {
  Trajectory t;
  for (StampNs s = from; s <= to; s += 10 * kMs) t.append(s, Pose3::Identity());
  return t;
}
}  // namespace

TEST(ReferenceStream, TheLeadBeforeTheFirstScanThenWhatCameSinceThePreviousOne) {
  const Trajectory ref = every10ms(1000 * kMs, 2000 * kMs);
  ReferenceStream stream(20 * kMs, 100 * kMs);
  EXPECT_EQ(stream.beforeScan('a', ref, 1300 * kMs),
            (std::vector<StampNs>{1210 * kMs, 1230 * kMs, 1250 * kMs, 1270 * kMs, 1290 * kMs, 1300 * kMs}));
  EXPECT_EQ(stream.beforeScan('a', ref, 1350 * kMs), (std::vector<StampNs>{1310 * kMs, 1330 * kMs, 1350 * kMs}));
  EXPECT_EQ(stream.beforeScan('b', ref, 1350 * kMs).size(), 6u);  // each robot its own
}

TEST(ReferenceStream, NothingWithoutAReference) {
  ReferenceStream stream;
  EXPECT_TRUE(stream.beforeScan('a', Trajectory{}, 1000 * kMs).empty());
}
