// SPDX-License-Identifier: Apache-2.0
// Ring (firmware/core/include/palp/fw/ring.hpp): the transmit buffer's bulk push and pop.
#include "palp/fw/ring.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace palp::fw {
namespace {

TEST(Ring, BulkPushAndPopKeepTheOrderAcrossTheWrap) {
  Ring<std::uint8_t, 8> r;
  const std::uint8_t a[] = {1, 2, 3, 4, 5, 6};
  ASSERT_TRUE(r.push_n(a, 6));
  std::uint8_t out[8] = {};
  ASSERT_EQ(r.pop_n(out, 4), 4u);  // head at 4: the next push wraps
  EXPECT_EQ(out[0], 1);
  EXPECT_EQ(out[3], 4);
  const std::uint8_t b[] = {7, 8, 9, 10, 11};
  ASSERT_TRUE(r.push_n(b, 5));  // 2 to the end of the storage, 3 from its start
  EXPECT_EQ(r.size(), 7u);
  ASSERT_EQ(r.pop_n(out, 8), 7u);  // fewer than asked: all there is
  const std::uint8_t want[] = {5, 6, 7, 8, 9, 10, 11};
  for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(out[k], want[k]) << k;
  EXPECT_TRUE(r.empty());
}

TEST(Ring, ABulkPushThatDoesNotFitPushesNothing) {
  Ring<int, 4> r;
  const int a[] = {1, 2, 3};
  ASSERT_TRUE(r.push_n(a, 3));
  EXPECT_FALSE(r.push_n(a, 2));
  EXPECT_EQ(r.size(), 3u);
  ASSERT_TRUE(r.push_n(a, 1));
  int out[4] = {};
  ASSERT_EQ(r.pop_n(out, 4), 4u);
  EXPECT_EQ(out[0], 1);
  EXPECT_EQ(out[2], 3);
  EXPECT_EQ(out[3], 1);
}

}  // namespace
}  // namespace palp::fw
