// The radio's payload store (comm/payload_store.hpp): what a receiver gets for an offered keyframe scan, and the
// payload sizes the radio is told, with and without xz.
#include <gtest/gtest.h>

#include <memory>

#include "cosmo/comm/payload_store.hpp"
#include "cosmo/comm/scan_compression.hpp"

using namespace cosmo;

namespace {
std::shared_ptr<const Scan> makeScan(StampNs stamp, int n) {
  auto scan = std::make_shared<Scan>();
  scan->stamp = stamp;
  for (int i = 0; i < n; ++i) {
    scan->points.emplace_back(0.5f * i, -0.25f * i, 1.0f + 0.01f * i);
    scan->intensity.push_back(static_cast<float>(i));
  }
  return scan;
}
}  // namespace

TEST(PayloadStore, WithoutCompressionDeliversTheOfferedScanItself) {
  comm::PayloadStore store(false);
  const auto scan = makeScan(1234, 100);
  const comm::PayloadStore::Sizes sizes = store.offer('a', 3, scan);
  EXPECT_EQ(sizes.raw, 1200u);
  EXPECT_EQ(sizes.payload, 1200u);
  EXPECT_EQ(store.deliver('a', 3), scan);  // the same object: no copy
  EXPECT_EQ(store.deliver('a', 4), nullptr);
  EXPECT_EQ(store.deliver('b', 3), nullptr);
}

TEST(PayloadStore, WithCompressionDeliversTheDecompressedPointsWithTheKeyframesStamp) {
  comm::PayloadStore store(true);
  const auto scan = makeScan(987654321, 500);
  const comm::PayloadStore::Sizes sizes = store.offer('b', 0, scan);
  EXPECT_EQ(sizes.raw, 6000u);
  EXPECT_EQ(sizes.payload, comm::compressScan(*scan).size());
  EXPECT_LT(sizes.payload, sizes.raw);
  const auto received = store.deliver('b', 0);
  ASSERT_TRUE(received);
  EXPECT_NE(received, scan);
  EXPECT_EQ(received->stamp, scan->stamp);
  EXPECT_EQ(received->points, scan->points);  // bit-exact x y z
  EXPECT_TRUE(received->intensity.empty());   // only the points travel
}

TEST(PayloadStore, RejectsAMissingScanAndABadPreset) {
  comm::PayloadStore store(true);
  EXPECT_THROW(store.offer('a', 0, nullptr), std::invalid_argument);
  EXPECT_THROW(comm::PayloadStore(true, 10), std::invalid_argument);
}
