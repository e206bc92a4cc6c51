// A front-end's bounded scan input (frontend/scan_queue.hpp): the oldest waiting scan is skipped when it is full,
// counted, and what is held never exceeds the capacity, also with a producer thread faster than the consumer.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "cosmo/frontend/scan_queue.hpp"

using cosmo::frontend::ScanQueue;

TEST(ScanQueue, SkipsTheOldestWaitingScanWhenFull) {
  ScanQueue<int> q(3);
  EXPECT_FALSE(q.push(1));
  EXPECT_FALSE(q.push(2));
  EXPECT_FALSE(q.push(3));
  EXPECT_TRUE(q.push(4));  // 1 skipped
  EXPECT_EQ(q.skipped(), 1u);
  EXPECT_EQ(q.size(), 3u);
  EXPECT_EQ(q.pop(), std::optional<int>(2));
  EXPECT_EQ(q.pop(), std::optional<int>(3));
  EXPECT_EQ(q.pop(), std::optional<int>(4));
  EXPECT_EQ(q.pop(), std::nullopt);
  EXPECT_EQ(q.peak(), 3u);
}

TEST(ScanQueue, CapacityZeroSkipsNothing) {
  ScanQueue<int> q(0);
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(q.push(i));
  EXPECT_EQ(q.size(), 1000u);
  EXPECT_EQ(q.skipped(), 0u);
  EXPECT_EQ(q.pop(), std::optional<int>(0));
}

TEST(ScanQueue, AFastProducerAndASlowConsumerStayBoundedAndLoseOnlyWhatIsCounted) {
  ScanQueue<int> q(4);
  constexpr int kScans = 20000;
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (int i = 0; i < kScans; ++i) q.push(i);
    done = true;
  });
  std::size_t processed = 0;
  int last = -1;
  bool in_order = true;
  while (!done || q.size() > 0) {
    if (const auto s = q.pop()) {
      in_order = in_order && *s > last;
      last = *s;
      ++processed;
      if (processed % 8 == 0) std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_TRUE(in_order) << "scans stay in their order";
  EXPECT_EQ(processed + q.skipped(), static_cast<std::size_t>(kScans));
  EXPECT_LE(q.peak(), 4u);
  EXPECT_EQ(last, kScans - 1) << "the newest scan is never skipped";
}
