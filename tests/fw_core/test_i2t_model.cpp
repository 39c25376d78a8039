// SPDX-License-Identifier: Apache-2.0
// The coil I²t model (firmware/core/include/palp/fw/i2t_model.hpp) through Safety::check(), tick
// by tick at 20 kHz, on the paper's protocols and on a 3 A hold.
//
// Parameters: the catalogue defaults I_c = 2.0 A, E_lim = 60 A²s, tau = 120 s (a rating of 1.5 A
// would trip the paper's 1D protocol: its rms current is 1.89 A for 250 s).
//
// Expected values, from the model's exact solution evaluated per staircase step (independently of
// this code, in double):
//   2D protocol (0.5 -> 3 A by 0.01 A every 25 ms and back, 3 repetitions, then 3 s at 0.5 A
//   while the arm moves on; 81 points): peak E = 11.4295 A²s (19 % of the limit);
//   1D protocol (the same staircase at 100 ms per step, 5 repetitions, then 3 s at 0.5 A;
//   10 positions): peak E = 43.1181 A²s (72 %; below the 80 % warning).
//   3 A hold from E = 0: t_trip = -tau ln(1 - E_lim / (tau (9 - I_c²))) = 12.6433 s
//   (9.2353 s with the catalogue's I_c = 1.5 A).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "palp/fw/i2t_model.hpp"
#include "palp/fw/safety.hpp"
#include "program_test_support.hpp"

namespace palp::fw {
namespace {

constexpr double kRate_Hz = 20000.0;
using test::kDt;

proto::Params recommended_params() {
  const proto::Params p;  // the catalogue defaults
  EXPECT_EQ(p.i2t_continuous_A, 2.0f);
  EXPECT_EQ(p.i2t_limit_A2s, 60.0f);
  EXPECT_EQ(p.i2t_tau_s, 120.0f);
  return p;
}

proto::Params rating_1_5A() {
  proto::Params p;
  p.i2t_continuous_A = 1.5f;
  return p;
}

/// Drives Safety tick by tick with measured current = set-point (the current loop settles in
/// 0.5 ms, negligible against 25 ms steps) and a host that keeps feeding the watchdog.
struct ProtocolRun {
  Safety safety;
  std::uint64_t tick = 0;
  double peak_A2s = 0.0;
  bool tripped = false;
  bool warned = false;

  explicit ProtocolRun(const proto::Params& p) : safety(p) {}

  void hold(float i_A, double seconds) {
    const auto ticks = static_cast<std::uint64_t>(std::llround(seconds * kRate_Hz));
    for (std::uint64_t k = 0; k < ticks; ++k, ++tick) {
      const std::uint64_t now_us = tick * 50u;
      safety.feed(now_us);
      const SafetyVerdict v = safety.check({i_A, i_A, 1000, true, kDt, now_us});
      tripped = tripped || v.tripped;
      warned = warned || safety.i2t_warning();
      peak_A2s = std::max(peak_A2s, static_cast<double>(safety.i2t().excess_A2s()));
    }
  }
  /// The paper's staircase: start 0.5 A, +0.01 A per step up to 3 A, symmetric unload.
  void staircase(double dwell_s, int repetitions) {
    for (int r = 0; r < repetitions; ++r) {
      for (int n = 50; n <= 300; ++n) hold(static_cast<float>(n) / 100.0f, dwell_s);
      for (int n = 299; n >= 50; --n) hold(static_cast<float>(n) / 100.0f, dwell_s);
    }
  }
};

TEST(I2tModel, Paper2DProtocolOf81PointsNeverTripsAndPeaksAt19PercentOfTheLimit) {
  ProtocolRun run(recommended_params());
  for (int point = 0; point < 81; ++point) {
    run.staircase(0.025, 3);
    run.hold(0.5f, 3.0);  // the arm moves to the next point and re-approaches
    ASSERT_FALSE(run.tripped) << "point " << point;
  }
  EXPECT_FALSE(run.warned);
  EXPECT_NEAR(run.peak_A2s, 11.4295, 11.4295 * 5e-3);
  EXPECT_EQ(run.tick, 65731500u);  // 81 x (3 x 501 x 25 ms + 3 s) = 3286.575 s
}

TEST(I2tModel, Paper1DProtocolOnTenPositionsNeverTripsAndPeaksAt72PercentOfTheLimit) {
  ProtocolRun run(recommended_params());
  for (int position = 0; position < 10; ++position) {
    run.staircase(0.100, 5);
    run.hold(0.5f, 3.0);
    ASSERT_FALSE(run.tripped) << "position " << position;
  }
  EXPECT_FALSE(run.warned);
  EXPECT_NEAR(run.peak_A2s, 43.1181, 43.1181 * 5e-3);
}

TEST(I2tModel, AContinuousRatingOf1_5AWouldTripThePaper1DProtocol) {
  // Why the catalogue's default is 2.0 A: with 1.5 A the 1D protocol trips in its first
  // position (E would reach 186 A²s of 60).
  ProtocolRun run(rating_1_5A());
  run.staircase(0.100, 5);
  EXPECT_TRUE(run.tripped);
}

/// Ticks until a hold of i_A trips, from a cold model.
std::uint64_t ticks_to_trip(const proto::Params& p, float i_A) {
  Safety safety(p);
  for (std::uint64_t k = 1; k < 100000000u; ++k) {
    safety.feed(k * 50u);
    const SafetyVerdict v = safety.check({i_A, i_A, 0, true, kDt, k * 50u});
    if (v.tripped) {
      EXPECT_EQ(v.new_fault, proto::FaultReason::i2t);
      EXPECT_EQ(v.i_set_A, 0.0f);
      return k;
    }
  }
  return 0;
}

TEST(I2tModel, ThreeAmpHoldTripsAt12_643sWithinOneTickOfTheClosedForm) {
  const double closed_form_s = 12.643261878939153;  // -120 ln(1 - 60 / (120 (9 - 4)))
  const std::uint64_t k = ticks_to_trip(recommended_params(), 3.0f);
  EXPECT_NEAR(static_cast<double>(k) / kRate_Hz, closed_form_s, 1.0 / kRate_Hz);
}

TEST(I2tModel, ThreeAmpHoldWithA1_5ARatingTripsAt9_235sWithinOneTick) {
  const double closed_form_s = 9.235324936335399;  // -120 ln(1 - 60 / (120 (9 - 2.25)))
  const std::uint64_t k = ticks_to_trip(rating_1_5A(), 3.0f);
  EXPECT_NEAR(static_cast<double>(k) / kRate_Hz, closed_form_s, 1.0 / kRate_Hz);
}

TEST(I2tModel, CurrentAtTheContinuousRatingNeverAccumulates) {
  I2tModel m;
  m.configure(2.0f, 60.0f, 120.0f);
  for (int k = 0; k < 20000 * 60; ++k) m.update(2.0f, kDt);  // one minute at 2.0 A
  EXPECT_EQ(m.excess_A2s(), 0.0f);
}

TEST(I2tModel, OneStepOf25msEqualsFiveHundredTicksBecauseTheUpdateIsExact) {
  I2tModel coarse;
  I2tModel fine;
  coarse.configure(2.0f, 60.0f, 120.0f);
  fine.configure(2.0f, 60.0f, 120.0f);
  for (int step = 0; step < 1200; ++step) {  // 10 s at 3 A, then 20 s at 0 A
    const float i = step < 400 ? 3.0f : 0.0f;
    coarse.update(i, 0.025f);
    for (int k = 0; k < 500; ++k) fine.update(i, kDt);
    ASSERT_NEAR(fine.excess_A2s(), coarse.excess_A2s(), 2e-4f) << "step " << step;
  }
  // 10 s at 3 A: 600 (1 - exp(-10/120)) = 47.973 A²s; at 0 A it cools to the floor 0 after
  // 120 ln((47.973 + 480) / 480) = 11.4 s.
  EXPECT_EQ(coarse.excess_A2s(), 0.0f);
}

TEST(I2tModel, TenSecondsAtThreeAmpsAccumulate47_973A2sJustBelowTheWarning) {
  I2tModel m;
  m.configure(2.0f, 60.0f, 120.0f);
  for (int k = 0; k < 200000; ++k) m.update(3.0f, kDt);
  EXPECT_NEAR(m.excess_A2s(), 47.97335f, 1e-3f);  // 600 (1 - exp(-1/12))
  EXPECT_NEAR(m.fraction(), 0.799556f, 2e-5f);
  EXPECT_FALSE(m.warning());
}

}  // namespace
}  // namespace palp::fw
