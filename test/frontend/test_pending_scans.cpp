// Scans waiting for their reference pose (frontend/pending_scans.hpp): in order, once covered or once a newer scan
// makes them too old; all at once when the reference is all there from the start.
#include <gtest/gtest.h>

#include "cosmo/frontend/pending_scans.hpp"

using namespace cosmo;
using namespace cosmo::frontend;

namespace {
constexpr StampNs kMs = 1000000ULL;
}

TEST(PendingScans, AScanGoesAheadOnceTheReferenceCoversItsStamp) {
  PendingScans<int> pending(500 * kMs, true);
  pending.push(1000 * kMs, 1);
  pending.push(1100 * kMs, 2);
  EXPECT_FALSE(pending.popReady(std::nullopt));
  EXPECT_FALSE(pending.popReady(999 * kMs));
  EXPECT_EQ(pending.popReady(1050 * kMs), 1);
  EXPECT_FALSE(pending.popReady(1050 * kMs));  // the second is not covered yet
  EXPECT_EQ(pending.popReady(1100 * kMs), 2);
  EXPECT_EQ(pending.size(), 0u);
}

TEST(PendingScans, AScanMuchOlderThanTheNewestGoesAheadWithoutItsReference) {
  PendingScans<int> pending(500 * kMs, true);
  pending.push(1000 * kMs, 1);
  pending.push(1500 * kMs, 2);
  EXPECT_FALSE(pending.popReady(std::nullopt));  // exactly max_wait newer: still waits
  pending.push(1501 * kMs, 3);
  EXPECT_EQ(pending.popReady(std::nullopt), 1);
  EXPECT_FALSE(pending.popReady(std::nullopt));
  EXPECT_EQ(pending.size(), 2u);
}

TEST(PendingScans, WithoutWaitingEveryScanGoesAheadInOrder) {
  PendingScans<int> pending(500 * kMs, false);
  pending.push(2000 * kMs, 1);
  pending.push(1000 * kMs, 2);
  EXPECT_EQ(pending.popReady(std::nullopt), 1);
  EXPECT_EQ(pending.popReady(std::nullopt), 2);
  EXPECT_FALSE(pending.popReady(std::nullopt));
}
