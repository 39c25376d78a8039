// SPDX-License-Identifier: Apache-2.0
// palpctl -v's rate limit on stream-gap lines (host/cli/gap_lines.hpp), on a made-up clock: 5
// lines a second let through, the rest counted and the count handed out with the next line let
// through, so that the lines printed plus the counts said add up to every gap.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <vector>

#include "gap_lines.hpp"

namespace palpctl {
namespace {

using namespace std::chrono_literals;
using Clock = GapLineLimiter::Clock;

TEST(GapLineLimiter, FiveLinesASecondPassAndTheRestAreCountedIntoTheNextOneThatPasses) {
  GapLineLimiter limit(5, 1s);
  const Clock::time_point t0{};
  // 100 gaps in the first second (one every 10 ms): the first 5 pass, 95 are counted
  int passed = 0;
  for (int k = 0; k < 100; ++k) {
    const auto r = limit.admit(t0 + k * 10ms);
    if (r) {
      EXPECT_EQ(*r, 0u) << k;  // nothing suppressed before them
      EXPECT_LT(k, 5);
      ++passed;
    }
  }
  EXPECT_EQ(passed, 5);
  // the next second's first line passes and says how many were left out before it
  const auto r = limit.admit(t0 + 1000ms);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(*r, 95u);
  EXPECT_EQ(limit.take_suppressed(), 0u);  // handed out once
}

TEST(GapLineLimiter, LinesPrintedPlusCountsSaidEqualEveryLine) {
  GapLineLimiter limit(5, 1s);
  const Clock::time_point t0{};
  std::uint64_t printed = 0, said = 0;
  const int lines = 1234;
  for (int k = 0; k < lines; ++k) {  // 1234 gaps, one every 3 ms: 3.7 s
    if (const auto r = limit.admit(t0 + k * 3ms)) {
      ++printed;
      said += *r;
    }
  }
  said += limit.take_suppressed();  // what palpctl says at exit
  EXPECT_EQ(printed + said, static_cast<std::uint64_t>(lines));
  EXPECT_EQ(printed, 20u);  // windows opened at 0, 1.002, 2.004, 3.006 s: 5 lines each
}

TEST(GapLineLimiter, FewLinesAllPassWithNothingSuppressed) {
  GapLineLimiter limit(5, 1s);
  const Clock::time_point t0{};
  for (int k = 0; k < 20; ++k) {  // 4 a second
    const auto r = limit.admit(t0 + k * 250ms);
    ASSERT_TRUE(r.has_value()) << k;
    EXPECT_EQ(*r, 0u);
  }
  EXPECT_EQ(limit.take_suppressed(), 0u);
}

}  // namespace
}  // namespace palpctl
