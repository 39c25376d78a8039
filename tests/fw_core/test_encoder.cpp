// SPDX-License-Identifier: Apache-2.0
// Encoder (firmware/core/include/palp/fw/encoder.hpp): 16-bit extension, velocity, index.
#include "palp/fw/encoder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include "program_test_support.hpp"

namespace palp::fw {
namespace {

using test::kDt;

/// The 16-bit hardware count that a true position maps to (the timer just wraps).
std::uint16_t timer_of(std::int64_t position) {
  return static_cast<std::uint16_t>(static_cast<std::uint64_t>(position) & 0xFFFFu);
}

TEST(Encoder, WrapsForwardAcross0xFFFFTo0WithoutAJump) {
  Encoder enc;
  enc.reset(0xFFFE, 100);
  enc.update(0xFFFF, kDt);
  EXPECT_EQ(enc.position_counts(), 101);
  enc.update(0x0000, kDt);
  EXPECT_EQ(enc.position_counts(), 102);
  enc.update(0x0003, kDt);
  EXPECT_EQ(enc.position_counts(), 105);
  EXPECT_EQ(enc.last_step_counts(), 3);
}

TEST(Encoder, WrapsBackwardAcross0To0xFFFFIntoNegativeCounts) {
  Encoder enc;
  enc.reset(0x0001, 0);
  enc.update(0x0000, kDt);
  EXPECT_EQ(enc.position_counts(), -1);
  enc.update(0xFFFF, kDt);
  EXPECT_EQ(enc.position_counts(), -2);
  enc.update(0xFFF0, kDt);
  EXPECT_EQ(enc.position_counts(), -17);
  EXPECT_EQ(enc.last_step_counts(), -15);
}

TEST(Encoder, ManyWrapsBothWaysStayExactToTheCount) {
  Encoder enc;
  std::int64_t truth = -5;
  enc.reset(timer_of(truth), static_cast<std::int32_t>(truth));
  // +30 000 counts per tick (just under half the 16-bit range) for 2000 ticks: 60 m, ~915 wraps.
  for (int k = 0; k < 2000; ++k) {
    truth += 30000;
    enc.update(timer_of(truth), kDt);
    ASSERT_EQ(enc.position_counts(), truth);
  }
  EXPECT_EQ(enc.position_counts(), 59999995);
  // and back past zero, at an uneven step
  for (int k = 0; k < 4000; ++k) {
    truth -= 17001;
    enc.update(timer_of(truth), kDt);
    ASSERT_EQ(enc.position_counts(), truth);
  }
  EXPECT_EQ(enc.position_counts(), 59999995 - 4000 * 17001);
  EXPECT_LT(enc.position_counts(), 0);
}

TEST(Encoder, VelocityOfA60000CountsPerSecondRampFollowsThe200HzFirstOrderLag) {
  // 3 counts per tick at 20 kHz = 60 000 counts/s (60 mm/s). The filter's answer after n ticks
  // is 60000 (1 - exp(-2 pi 200 n dt)): 38 044 after 16 ticks (0.8 ms, about one time
  // constant), 59 888 after 100 ticks.
  Encoder enc;
  enc.reset(0);
  std::int64_t truth = 0;
  for (int n = 1; n <= 100; ++n) {
    truth += 3;
    enc.update(timer_of(truth), kDt);
    if (n == 16) {
      EXPECT_NEAR(enc.velocity_counts_per_s(), 38044.1, 38044.1 * 1e-4);
    }
  }
  EXPECT_NEAR(enc.velocity_counts_per_s(), 59888.0, 59888.0 * 1e-4);
}

TEST(Encoder, SlowRampOf1000CountsPerSecondAveragesToItsSpeed) {
  // One count every 20 ticks: the raw difference is 0 or 20 000 counts/s; the filtered estimate
  // averages to the true 1000 counts/s (mean over whole periods of the count pattern).
  Encoder enc;
  enc.reset(0);
  double sum = 0.0;
  int samples = 0;
  for (int k = 1; k <= 40000; ++k) {  // 2 s
    enc.update(timer_of(k / 20), kDt);
    if (k > 20000) {
      sum += enc.velocity_counts_per_s();
      ++samples;
    }
  }
  EXPECT_NEAR(sum / samples, 1000.0, 5.0);
  EXPECT_EQ(enc.position_counts(), 2000);
}

TEST(Encoder, VelocityIsNegativeMovingTowardMinusZAcrossTheWrap) {
  Encoder enc;
  std::int64_t truth = 2000;
  enc.reset(timer_of(truth), 2000);
  for (int k = 0; k < 400; ++k) {  // -10 counts per tick = -200 000 counts/s, through 0
    truth -= 10;
    enc.update(timer_of(truth), kDt);
  }
  EXPECT_EQ(enc.position_counts(), -2000);
  EXPECT_NEAR(enc.velocity_counts_per_s(), -200000.0f, 200.0f);
}

TEST(Encoder, IndexLatchHoldsTheExtendedCountAtThePulseWhileTheCoilMovesOn) {
  Encoder enc;
  enc.reset(0xFFF0, 70000);  // near the wrap, far from the timer's own count
  enc.update(0xFFF8, kDt);   // 70008
  enc.latch_index();
  EXPECT_TRUE(enc.index_latched());
  EXPECT_EQ(enc.index_position_counts(), 70008);
  enc.update(0x0010, kDt);   // 70032: the latch keeps 70008
  EXPECT_EQ(enc.position_counts(), 70032);
  EXPECT_EQ(enc.index_position_counts(), 70008);
  enc.clear_index();
  EXPECT_FALSE(enc.index_latched());
}

TEST(Encoder, IndexCapturedByTheTimerIsExtendedAcrossTheWrap) {
  Encoder enc;
  enc.reset(0xFFFD, -3);
  enc.update(0x0004, kDt);  // position 4
  // The timer captured 0xFFFE at the pulse, before the wrap: position -2.
  enc.latch_index_at(0xFFFE);
  EXPECT_EQ(enc.index_position_counts(), -2);
  // A capture just after the last read: position 6.
  enc.latch_index_at(0x0006);
  EXPECT_EQ(enc.index_position_counts(), 6);
}

TEST(Encoder, ResetClearsVelocityAndTheIndexLatch) {
  Encoder enc;
  enc.reset(0);
  for (int k = 1; k <= 50; ++k) enc.update(timer_of(5 * k), kDt);
  enc.latch_index();
  EXPECT_GT(enc.velocity_counts_per_s(), 0.0f);
  enc.reset(123, 42);
  EXPECT_EQ(enc.position_counts(), 42);
  EXPECT_EQ(enc.velocity_counts_per_s(), 0.0f);
  EXPECT_FALSE(enc.index_latched());
  enc.update(124, kDt);
  EXPECT_EQ(enc.position_counts(), 43);
}

}  // namespace
}  // namespace palp::fw
