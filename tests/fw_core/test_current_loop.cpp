// SPDX-License-Identifier: Apache-2.0
// CurrentLoop (firmware/core/include/palp/fw/current_loop.hpp) against an exact RL coil model.
//
// The coil in these tests: i' = (v - R i) / L with R = 5.8 ohm, L = 2.07 mH, the voltage held
// constant over each tick (zero-order hold) and integrated exactly with exp, in double, in 10
// sub-steps per tick so the peak between ticks is seen too.
//
// Expected values (derived in current_loop.hpp, wc = 2 pi 1500 rad/s):
//   sampled unit-step response i(k) = 1 - exp(-wc k dt);
//   1 % settling at ln(100) / wc = 488.6 us -> first settled tick is 500 us at 20 and 40 kHz
//   (at 450 us / 475 us the error is still 1.44 % / 1.14 %); no overshoot.
#include "palp/fw/current_loop.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace palp::fw {
namespace {

constexpr double kR = 5.8;
constexpr double kL = 2.07e-3;
constexpr double kWc = 2.0 * 3.14159265358979323846 * 1500.0;
constexpr int kSubsteps = 10;

struct RlCoil {
  double i_A = 0.0;
  double peak_A = 0.0;
  double trough_A = 0.0;
  /// Holds v_V for dt_s; exact solution of the RL equation, evaluated at kSubsteps points.
  void apply(double v_V, double dt_s) {
    const double h = dt_s / kSubsteps;
    const double a = std::exp(-kR * h / kL);
    for (int s = 0; s < kSubsteps; ++s) {
      i_A = a * i_A + (1.0 - a) * v_V / kR;
      peak_A = std::max(peak_A, i_A);
      trough_A = std::min(trough_A, i_A);
    }
  }
};

struct StepRun {
  std::vector<double> i_A;  // current at the end of each tick
  std::vector<float> v_V;   // voltage applied during each tick
  double peak_A = 0.0;
  double trough_A = 0.0;
};

/// Runs a step from i0 to `target_A` for `ticks` ticks. delay_ticks = 1 applies each voltage one
/// tick late (a PWM that loads the new duty at the next period).
StepRun run_step(CurrentLoop& loop, double rate_Hz, float target_A, int ticks,
                 int delay_ticks = 0, double i0_A = 0.0) {
  const float dt = static_cast<float>(1.0 / rate_Hz);
  RlCoil coil;
  coil.i_A = coil.peak_A = coil.trough_A = i0_A;
  StepRun run;
  float pending_V = 0.0f;
  for (int k = 0; k < ticks; ++k) {
    const float v = loop.update(target_A, static_cast<float>(coil.i_A), dt);
    const float applied = delay_ticks ? pending_V : v;
    pending_V = v;
    coil.apply(applied, 1.0 / rate_Hz);
    run.i_A.push_back(coil.i_A);
    run.v_V.push_back(v);
  }
  run.peak_A = coil.peak_A;
  run.trough_A = coil.trough_A;
  return run;
}

/// Time (s) from which the current stays within +-tol of target to the end of the run.
double settle_time_s(const StepRun& run, double rate_Hz, double target, double tol) {
  std::size_t last_outside = 0;  // ticks; 0: inside from the first sample on
  for (std::size_t k = 0; k < run.i_A.size(); ++k)
    if (std::fabs(run.i_A[k] - target) > tol) last_outside = k + 1;
  return static_cast<double>(last_outside + 1) / rate_Hz;
}

TEST(CurrentLoop, GainsAre14_49VPerAAnd43590VPerAsAt20kHzAnd16_78And48701At40kHz) {
  const CurrentLoopGains g20 = current_loop_gains({}, 1.0f / 20000.0f);
  EXPECT_NEAR(g20.kp_V_per_A, 14.4926417, 14.4926417 * 1e-5);
  EXPECT_NEAR(g20.ki_V_per_A_s, 43589.502, 43589.502 * 1e-5);
  const CurrentLoopGains g40 = current_loop_gains({}, 1.0f / 40000.0f);
  EXPECT_NEAR(g40.kp_V_per_A, 16.7796121, 16.7796121 * 1e-5);
  EXPECT_NEAR(g40.ki_V_per_A_s, 48701.142, 48701.142 * 1e-5);
}

TEST(CurrentLoop, GainsTendToLOmegaAndROmegaAsTheTickShrinks) {
  const CurrentLoopGains g = current_loop_gains({}, 1e-8f);
  EXPECT_NEAR(g.kp_V_per_A, kL * kWc, kL * kWc * 5e-4);  // 19.509 V/A
  EXPECT_NEAR(g.ki_V_per_A_s, kR * kWc, kR * kWc * 5e-4);  // 54 664 V/(A s)
}

TEST(CurrentLoop, SampledStepResponseIsTheFirstOrderLagOf1500HzAt20And40kHz) {
  for (const double rate_Hz : {20000.0, 40000.0}) {
    CurrentLoop loop;
    const StepRun run = run_step(loop, rate_Hz, 1.0f, static_cast<int>(rate_Hz * 2e-3));
    for (std::size_t k = 0; k < run.i_A.size(); ++k) {
      const double t = static_cast<double>(k + 1) / rate_Hz;
      ASSERT_NEAR(run.i_A[k], 1.0 - std::exp(-kWc * t), 1e-4) << "rate " << rate_Hz << " tick " << k;
    }
  }
}

TEST(CurrentLoop, OneAmpStepSettlesToOnePercentAt500usWithOvershootBelowPointOnePercent) {
  for (const double rate_Hz : {20000.0, 40000.0}) {
    CurrentLoop loop;
    const StepRun run = run_step(loop, rate_Hz, 1.0f, static_cast<int>(rate_Hz * 5e-3));
    EXPECT_NEAR(settle_time_s(run, rate_Hz, 1.0, 0.01), 500e-6, 1e-9) << "rate " << rate_Hz;
    EXPECT_LT(run.peak_A, 1.001) << "rate " << rate_Hz;  // between ticks too
    EXPECT_FALSE(loop.saturated());
    EXPECT_LT(*std::max_element(run.v_V.begin(), run.v_V.end()), 24.0f);  // never at the rail
    EXPECT_NEAR(run.i_A.back(), 1.0, 1e-5);
  }
}

TEST(CurrentLoop, ThreeAmpStepSaturatesAt24VAndEndsWithoutWindupOvershoot) {
  for (const double rate_Hz : {20000.0, 40000.0}) {
    CurrentLoop loop;
    const float dt = static_cast<float>(1.0 / rate_Hz);
    EXPECT_EQ(loop.update(3.0f, 0.0f, dt), 24.0f);  // Kp * 3 A is over 43 V
    EXPECT_TRUE(loop.saturated());
    loop.reset();
    const StepRun run = run_step(loop, rate_Hz, 3.0f, static_cast<int>(rate_Hz * 10e-3));
    EXPECT_EQ(run.v_V.front(), 24.0f);
    for (const float v : run.v_V) ASSERT_LE(std::fabs(v), 24.0f);
    EXPECT_LT(run.peak_A, 3.0 * 1.01) << "rate " << rate_Hz;   // < 1 % overshoot
    // The rise at the rail alone takes L/R ln(4.138 / (4.138 - 3)) = 0.46 ms.
    EXPECT_LT(settle_time_s(run, rate_Hz, 3.0, 0.03), 2e-3) << "rate " << rate_Hz;
    EXPECT_FALSE(loop.saturated());
  }
}

TEST(CurrentLoop, SameSaturatedStepWithoutAntiWindupWouldOvershootMoreThanTenPercent) {
  // The scenario is a real test of the anti-windup: a plain PI with the same gains and the same
  // 24 V rail overshoots by about 12 %.
  const double rate_Hz = 20000.0;
  const float dt = static_cast<float>(1.0 / rate_Hz);
  const CurrentLoopGains g = current_loop_gains({}, dt);
  RlCoil coil;
  float integrator = 0.0f;
  for (int k = 0; k < 200; ++k) {
    const float e = 3.0f - static_cast<float>(coil.i_A);
    integrator += g.ki_V_per_A_s * dt * e;
    const float v = std::clamp(g.kp_V_per_A * e + integrator, -24.0f, 24.0f);
    coil.apply(v, dt);
  }
  EXPECT_GT(coil.peak_A, 3.0 * 1.10);
}

TEST(CurrentLoop, ReversingStepFromPlusToMinusThreeAmpsSaturatesAtMinus24VWithoutOvershoot) {
  CurrentLoop loop;
  const double rate_Hz = 20000.0;
  run_step(loop, rate_Hz, 3.0f, 200);  // settle at +3 A (integrator near R * 3 A)
  const StepRun run = run_step(loop, rate_Hz, -3.0f, 200, 0, 3.0);
  EXPECT_EQ(run.v_V.front(), -24.0f);
  EXPECT_GT(run.trough_A, -3.0 * 1.01);
  EXPECT_NEAR(run.i_A.back(), -3.0, 0.03);
}

TEST(CurrentLoop, OneTickPwmDelayStaysStableWithOvershootBelowTenPercentAt20kHz) {
  // Closed-loop poles with the delay: z^2 - z + g = 0, g = 1 - exp(-wc dt) = 0.3757 at 20 kHz:
  // |z| = 0.613, overshoot about 8.5 %; at 40 kHz the poles are real (no overshoot).
  for (const double rate_Hz : {20000.0, 40000.0}) {
    CurrentLoop loop;
    const StepRun run = run_step(loop, rate_Hz, 1.0f, static_cast<int>(rate_Hz * 5e-3), 1);
    EXPECT_LT(run.peak_A, 1.10) << "rate " << rate_Hz;
    EXPECT_LT(settle_time_s(run, rate_Hz, 1.0, 0.01), 1e-3) << "rate " << rate_Hz;
  }
}

TEST(CurrentLoop, OutputStaysWithinAReducedSupplyOf12V) {
  CurrentLoop loop;
  loop.set_supply_V(12.0f);
  const StepRun up = run_step(loop, 20000.0, 3.0f, 400);
  for (const float v : up.v_V) ASSERT_LE(std::fabs(v), 12.0f);
  EXPECT_EQ(up.v_V.front(), 12.0f);
  // 12 V drives at most 12 / 5.8 = 2.069 A: the loop sits at the rail without winding up.
  EXPECT_NEAR(up.i_A.back(), 12.0 / kR, 1e-3);
  EXPECT_TRUE(loop.saturated());
  EXPECT_LE(std::fabs(loop.integrator_V()), 12.0f);
}

TEST(CurrentLoop, ResetClearsTheIntegratorAndTheSaturationFlag) {
  CurrentLoop loop;
  (void)loop.update(3.0f, 0.0f, 5e-5f);
  (void)loop.update(3.0f, 2.0f, 5e-5f);
  EXPECT_NE(loop.integrator_V(), 0.0f);
  loop.reset();
  EXPECT_EQ(loop.integrator_V(), 0.0f);
  EXPECT_FALSE(loop.saturated());
  EXPECT_EQ(loop.update(0.0f, 0.0f, 5e-5f), 0.0f);
}

TEST(CurrentLoop, NonPositiveTickOrNaNMeasurementGivesZeroVolts) {
  CurrentLoop loop;
  EXPECT_EQ(loop.update(1.0f, 0.0f, 0.0f), 0.0f);
  EXPECT_EQ(loop.update(1.0f, 0.0f, -5e-5f), 0.0f);
  EXPECT_EQ(loop.update(1.0f, std::nanf(""), 5e-5f), 0.0f);
  EXPECT_EQ(loop.integrator_V(), 0.0f);
}

}  // namespace
}  // namespace palp::fw
