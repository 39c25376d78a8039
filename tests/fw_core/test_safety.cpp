// SPDX-License-Identifier: Apache-2.0
// Safety (firmware/core/include/palp/fw/safety.hpp): clamp, overcurrent, travel, I²t latch,
// heartbeat watchdog on its own clock, external trips, clear().
#include "palp/fw/safety.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include "program_test_support.hpp"

namespace palp::fw {
namespace {

using proto::FaultReason;
using test::kDt;

proto::Params test_params() {
  proto::Params p;  // clamp 3.2 A, heartbeat 500 ms (catalogue defaults)
  p.i2t_continuous_A = 2.0f;
  p.travel_min_counts = -2000;  // the tests' own limits, independent of the defaults
  p.travel_max_counts = 25000;
  return p;
}

SafetyInputs idle_at(std::uint64_t wd_us) {
  SafetyInputs in;
  in.dt_s = kDt;
  in.watchdog_now_us = wd_us;
  return in;
}

SafetyInputs running(float i_A, std::uint64_t wd_us) {
  SafetyInputs in = idle_at(wd_us);
  in.i_request_A = i_A;
  in.i_measured_A = i_A;
  return in;
}

TEST(Safety, ClampLimitsTheSetPointTo3_2AEitherWayAndReportsIt) {
  Safety s(test_params());
  SafetyVerdict v = s.check(running(4.0f, 0));
  EXPECT_EQ(v.i_set_A, 3.2f);
  EXPECT_TRUE(v.clamped);
  EXPECT_FALSE(v.tripped);
  v = s.check(running(-3.5f, 0));
  EXPECT_EQ(v.i_set_A, -3.2f);
  EXPECT_TRUE(v.clamped);
  v = s.check(running(3.2f, 0));
  EXPECT_EQ(v.i_set_A, 3.2f);
  EXPECT_FALSE(v.clamped);
  EXPECT_FALSE(s.tripped());
}

TEST(Safety, OvercurrentBeyondClampPlusQuarterAmpFor1msTripsWithZeroSetPointInThatCall) {
  Safety s(test_params());
  SafetyInputs in = running(3.0f, 0);
  in.i_measured_A = 3.46f;  // beyond 3.2 + 0.25
  for (int tick = 1; tick <= 19; ++tick) {
    const SafetyVerdict v = s.check(in);
    ASSERT_FALSE(v.tripped) << tick;
    ASSERT_EQ(v.i_set_A, 3.0f);
  }
  const SafetyVerdict v = s.check(in);  // the 20th tick: 1 ms
  EXPECT_TRUE(v.tripped);
  EXPECT_EQ(v.new_fault, FaultReason::overcurrent);
  EXPECT_EQ(v.i_set_A, 0.0f);
  EXPECT_EQ(s.fault(), FaultReason::overcurrent);
  EXPECT_EQ(s.fault_detail(), 34600);  // 0.1 mA
  // latched: the next call is still tripped but is not a new fault
  const SafetyVerdict next = s.check(running(1.0f, 0));
  EXPECT_TRUE(next.tripped);
  EXPECT_EQ(next.new_fault, FaultReason::none);
  EXPECT_EQ(next.i_set_A, 0.0f);
}

TEST(Safety, CurrentJustWithinTheMarginOrBrieflyBeyondItNeverTrips) {
  Safety s(test_params());
  SafetyInputs in = running(3.2f, 0);
  for (int tick = 0; tick < 20000; ++tick) {
    in.i_measured_A = 3.44f;
    ASSERT_FALSE(s.check(in).tripped);
  }
  for (int burst = 0; burst < 100; ++burst) {  // 19 ticks beyond, 1 tick back: never 1 ms
    in.i_measured_A = 3.6f;
    for (int k = 0; k < 19; ++k) ASSERT_FALSE(s.check(in).tripped);
    in.i_measured_A = 3.0f;
    ASSERT_FALSE(s.check(in).tripped);
  }
}

TEST(Safety, OvercurrentClearIsRefusedWhileTheCurrentStaysHighAndAcceptedOnceItFalls) {
  Safety s(test_params());
  SafetyInputs in = running(3.0f, 0);
  in.i_measured_A = -3.6f;
  for (int k = 0; k < 20; ++k) (void)s.check(in);
  ASSERT_EQ(s.fault(), FaultReason::overcurrent);
  EXPECT_EQ(s.clear(0), ClearResult::cause_persists);
  EXPECT_TRUE(s.tripped());
  in.i_measured_A = 0.1f;
  EXPECT_EQ(s.check(in).i_set_A, 0.0f);  // still latched until cleared
  EXPECT_EQ(s.clear(0), ClearResult::cleared);
  EXPECT_FALSE(s.tripped());
  EXPECT_EQ(s.check(in).i_set_A, 3.0f);
}

TEST(Safety, TravelBeyondEitherLimitTripsWithTheCountAndClearsOnlyBackInside) {
  Safety s(test_params());
  SafetyInputs in = running(1.0f, 0);
  in.encoder_counts = 25000;  // at the limit is allowed
  EXPECT_FALSE(s.check(in).tripped);
  in.encoder_counts = 25001;
  const SafetyVerdict v = s.check(in);
  EXPECT_TRUE(v.tripped);
  EXPECT_EQ(v.new_fault, FaultReason::travel_limit);
  EXPECT_EQ(v.i_set_A, 0.0f);
  EXPECT_EQ(s.fault_detail(), 25001);
  EXPECT_EQ(s.clear(0), ClearResult::cause_persists);
  in.encoder_counts = 24000;
  (void)s.check(in);
  EXPECT_EQ(s.clear(0), ClearResult::cleared);

  in.encoder_counts = -2001;
  EXPECT_EQ(s.check(in).new_fault, FaultReason::travel_limit);
  EXPECT_EQ(s.fault_detail(), -2001);
}

TEST(Safety, I2tTripLatchesAndClearIsRefusedUntilTheModelCoolsToHalfItsLimit) {
  // I_c = 2 A, E_lim = 60 A²s, tau = 120 s. After the trip at 3 A the current is 0:
  // E' = -4 - E/120, so E falls from 60 to 30 A²s in 120 ln(540 / 510) = 6.859 s.
  Safety s(test_params());
  std::uint64_t now_us = 0;
  while (!s.tripped()) {
    now_us += 50;
    s.feed(now_us);
    (void)s.check(running(3.0f, now_us));
  }
  EXPECT_EQ(s.fault(), FaultReason::i2t);
  EXPECT_EQ(s.fault_detail(), 30000);  // 3 A in 0.1 mA
  EXPECT_GE(s.i2t_fraction(), 1.0f);
  EXPECT_EQ(s.clear(now_us), ClearResult::cause_persists);
  SafetyInputs cooling = idle_at(now_us);
  for (int k = 0; k < 20000 * 68 / 10; ++k) (void)s.check(cooling);  // 6.8 s
  EXPECT_EQ(s.clear(now_us), ClearResult::cause_persists);
  for (int k = 0; k < 20000 / 10; ++k) (void)s.check(cooling);  // to 6.9 s
  EXPECT_LE(s.i2t_fraction(), 0.5f);
  EXPECT_EQ(s.clear(now_us), ClearResult::cleared);
}

TEST(Safety, WatchdogIgnoresTheControlClockRacingAhead) {
  // Control time runs 1000x faster than the watchdog clock (a simulator at full speed): 50 s of
  // control ticks while 50 ms of watchdog time pass. No trip.
  Safety s(test_params());
  s.feed(1000000);
  for (int k = 0; k < 1000000; ++k) {
    const std::uint64_t wd_us = 1000000 + static_cast<std::uint64_t>(k) / 20u;  // 0.05 us/tick
    ASSERT_FALSE(s.check(running(1.0f, wd_us)).tripped) << k;
  }
  EXPECT_TRUE(s.heartbeat_armed());
}

TEST(Safety, WatchdogTripsWhenItsOwnClockPassesTheTimeoutWithoutAFeed) {
  // One control tick while 500 ms of watchdog time pass (a simulator paused or slowed down):
  // the timeout is judged on the watchdog clock only.
  Safety s(test_params());
  s.feed(2000000);
  EXPECT_FALSE(s.check(running(1.0f, 2500000)).tripped);  // exactly 500 ms: not yet
  const SafetyVerdict v = s.check(running(1.0f, 2500001));
  EXPECT_TRUE(v.tripped);
  EXPECT_EQ(v.new_fault, FaultReason::heartbeat_timeout);
  EXPECT_EQ(v.i_set_A, 0.0f);
  EXPECT_EQ(s.fault_detail(), 0);  // ms late
}

TEST(Safety, WatchdogIsArmedOnlyByANonZeroRequestOrARunningProgram) {
  Safety s(test_params());
  s.feed(0);
  EXPECT_FALSE(s.check(idle_at(10000000)).tripped);  // 10 s without a feed, idle: fine
  EXPECT_FALSE(s.heartbeat_armed());
  SafetyInputs program = idle_at(10000000);
  program.program_running = true;  // a program at 0 A still arms it
  const SafetyVerdict v = s.check(program);
  EXPECT_TRUE(s.heartbeat_armed());
  EXPECT_EQ(v.new_fault, FaultReason::heartbeat_timeout);
  EXPECT_EQ(s.fault_detail(), 9500);  // 10 s - 0.5 s late
}

TEST(Safety, FeedingKeepsAnArmedWatchdogQuietAndHeartbeatClearNeedsAFeed) {
  Safety s(test_params());
  for (std::uint64_t t = 0; t <= 60000000; t += 400000) {  // a feed every 400 ms for 60 s
    s.feed(t);
    ASSERT_FALSE(s.check(running(0.5f, t + 399000)).tripped);
  }
  (void)s.check(running(0.5f, 70000000));  // 10 s silence
  ASSERT_EQ(s.fault(), FaultReason::heartbeat_timeout);
  EXPECT_EQ(s.clear(70000000), ClearResult::cause_persists);
  s.feed(70000100);  // the FaultClear request itself
  EXPECT_EQ(s.clear(70000100), ClearResult::cleared);
}

TEST(Safety, ExternalTripLatchesTheFirstReasonAndZeroesTheNextSetPoint) {
  Safety s(test_params());
  s.trip(FaultReason::host_request, 0);
  EXPECT_TRUE(s.tripped());
  s.trip(FaultReason::control_overrun, 3);  // the first fault stays
  EXPECT_EQ(s.fault(), FaultReason::host_request);
  const SafetyVerdict v = s.check(running(1.0f, 0));
  EXPECT_TRUE(v.tripped);
  EXPECT_EQ(v.i_set_A, 0.0f);
  EXPECT_EQ(s.clear(0), ClearResult::cleared);
  EXPECT_EQ(s.clear(0), ClearResult::not_latched);
}

TEST(Safety, SecondFaultInTheSameLatchDoesNotOverwriteTheFirst) {
  Safety s(test_params());
  SafetyInputs in = running(1.0f, 0);
  in.encoder_counts = 30000;
  (void)s.check(in);
  ASSERT_EQ(s.fault(), FaultReason::travel_limit);
  in.i_measured_A = 4.0f;
  for (int k = 0; k < 40; ++k) EXPECT_EQ(s.check(in).new_fault, FaultReason::none);  // not reported
  EXPECT_EQ(s.fault(), FaultReason::travel_limit);
  EXPECT_EQ(s.fault_detail(), 30000);
}

TEST(Safety, NonFiniteRequestTripsInternalAtOnce) {
  Safety s(test_params());
  const SafetyVerdict v = s.check(running(std::nanf(""), 0));
  EXPECT_TRUE(v.tripped);
  EXPECT_EQ(v.new_fault, FaultReason::internal);
  EXPECT_EQ(v.i_set_A, 0.0f);
  EXPECT_EQ(s.fault_detail(), 1);  // 1: the request, 2: the measurement (SPEC.md §6.2)
}

TEST(Safety, ConfigureAppliesANewClampAndKeepsTheLatch) {
  Safety s(test_params());
  proto::Params p = test_params();
  p.current_clamp_A = 1.0f;
  s.configure(p);
  EXPECT_EQ(s.check(running(2.0f, 0)).i_set_A, 1.0f);
  s.trip(FaultReason::host_request, 0);
  s.configure(test_params());
  EXPECT_TRUE(s.tripped());
}

}  // namespace
}  // namespace palp::fw
