// SPDX-License-Identifier: Apache-2.0
// SpscQueue and OverflowCounter (firmware/core/include/palp/fw/spsc_queue.hpp).
#include "palp/fw/spsc_queue.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <thread>

namespace palp::fw {
namespace {

TEST(SpscQueue, PopsItemsInPushOrder) {
  SpscQueue<int, 8> q;
  for (int k = 1; k <= 5; ++k) ASSERT_TRUE(q.push(k * 10));
  EXPECT_EQ(q.size(), 5u);
  for (int k = 1; k <= 5; ++k) {
    int out = 0;
    ASSERT_TRUE(q.pop(out));
    EXPECT_EQ(out, k * 10);
  }
  EXPECT_TRUE(q.empty());
}

TEST(SpscQueue, HoldsExactlyNItemsAndRefusesTheNextWithoutLosingAny) {
  SpscQueue<std::uint32_t, 4> q;
  EXPECT_EQ(q.capacity(), 4u);
  for (std::uint32_t k = 0; k < 4; ++k) ASSERT_TRUE(q.push(k));
  EXPECT_TRUE(q.full());
  EXPECT_FALSE(q.push(99));
  EXPECT_EQ(q.size(), 4u);
  std::uint32_t out = 0;
  ASSERT_TRUE(q.pop(out));
  EXPECT_EQ(out, 0u);
  EXPECT_TRUE(q.push(4));  // a freed slot is usable again
  for (std::uint32_t want = 1; want <= 4; ++want) {
    ASSERT_TRUE(q.pop(out));
    EXPECT_EQ(out, want);
  }
}

TEST(SpscQueue, EmptyQueuePopsNothingAndPeeksNull) {
  SpscQueue<int, 2> q;
  int out = 7;
  EXPECT_FALSE(q.pop(out));
  EXPECT_EQ(out, 7);  // untouched
  EXPECT_EQ(q.peek(), nullptr);
  EXPECT_FALSE(q.drop_front());
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.size(), 0u);
}

TEST(SpscQueue, PeekShowsTheOldestItemWithoutRemovingIt) {
  SpscQueue<int, 4> q;
  ASSERT_TRUE(q.push(1));
  ASSERT_TRUE(q.push(2));
  ASSERT_NE(q.peek(), nullptr);
  EXPECT_EQ(*q.peek(), 1);
  EXPECT_EQ(q.size(), 2u);
  EXPECT_TRUE(q.drop_front());
  ASSERT_NE(q.peek(), nullptr);
  EXPECT_EQ(*q.peek(), 2);
}

TEST(SpscQueue, WrapsAroundTheRingOverManyCyclesKeepingOrder) {
  SpscQueue<std::uint32_t, 8> q;
  std::uint32_t next_in = 0;
  std::uint32_t next_out = 0;
  // Uneven batches so the fill level and the slot positions keep changing: 100000 cycles wrap
  // the 8-slot ring tens of thousands of times.
  for (int cycle = 0; cycle < 100000; ++cycle) {
    const int pushes = 1 + cycle % 7;
    for (int k = 0; k < pushes && q.push(next_in); ++k) ++next_in;
    const int pops = 1 + (cycle * 3) % 6;
    std::uint32_t out = 0;
    for (int k = 0; k < pops && q.pop(out); ++k) {
      ASSERT_EQ(out, next_out);
      ++next_out;
    }
    ASSERT_EQ(q.size(), next_in - next_out);
  }
  EXPECT_GT(next_out, 8u * 10000u);
}

TEST(SpscQueue, ConcurrentProducerAndConsumerLoseAndReorderNothing) {
  SpscQueue<std::uint32_t, 64> q;
  constexpr std::uint32_t kItems = 1000000;
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (std::uint32_t k = 0; k < kItems; ++k)
      while (!q.push(k)) std::this_thread::yield();
    done.store(true);
  });
  std::uint32_t expected = 0;
  bool in_order = true;
  while (expected < kItems) {
    std::uint32_t out = 0;
    if (q.pop(out)) {
      in_order = in_order && out == expected;
      ++expected;
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_TRUE(in_order);
  EXPECT_TRUE(done.load());
  EXPECT_TRUE(q.empty());
}

TEST(OverflowCounter, CountsEachRefusedPushAndReportsOnlyNewOnes) {
  SpscQueue<int, 2> q;
  OverflowCounter overflows;
  EXPECT_TRUE(overflows.push(q, 1));
  EXPECT_TRUE(overflows.push(q, 2));
  EXPECT_FALSE(overflows.push(q, 3));
  EXPECT_FALSE(overflows.push(q, 4));
  EXPECT_EQ(overflows.total(), 2u);
  EXPECT_EQ(overflows.take_new(), 2u);
  EXPECT_EQ(overflows.take_new(), 0u);
  overflows.record();
  EXPECT_EQ(overflows.total(), 3u);
  EXPECT_EQ(overflows.take_new(), 1u);
}

}  // namespace
}  // namespace palp::fw
