// SPDX-License-Identifier: Apache-2.0
// Force-limited ramps (force_limit.hpp): the top current from the paper's force model, the
// staircase landing on it, the firmware's I2t model over a ramp, and the refusals' messages.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "palp/error.hpp"
#include "palp/force_limit.hpp"

namespace force_limit_test {

using palp::CoilLimits;
using palp::IndentationPreset;
using palp::IndentationSettings;

std::string refusal(const IndentationSettings& s, double force_N, const CoilLimits& lim = {}) {
  try {
    palp::check_max_force(s, force_N, lim);
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ForceLimit, TopCurrentIsIcPlusForceAndSpringAtTheDepthOverKf) {
  const palp::analysis::IndentationParams a;  // K_f 2.918 N/A, I_c 0.5 A, k_v 43.9 N/m
  EXPECT_NEAR(palp::top_current_for_force_A(a, 5.0, 2e-3), 0.5 + (5.0 + 0.0878) / 2.918, 1e-12);
  EXPECT_NEAR(palp::top_current_for_force_A(a, 7.17, 0.0), 0.5 + 7.17 / 2.918, 1e-12);
}

TEST(ForceLimit, StaircaseLandsOnTheTopWithAStepNoLargerThanAsked) {
  const IndentationSettings base = IndentationSettings::preset(IndentationPreset::two_d);
  const IndentationSettings s = palp::settings_for_max_force(base, 5.0, 2e-3);
  const double top = 0.5 + (5.0 + 0.0878) / 2.918;  // 2.24360 A: 174.36 steps of 0.01 A
  EXPECT_NEAR(s.stop_A, top, 1e-12);
  EXPECT_NEAR(s.step_A, (top - 0.5) / 175, 1e-12);
  EXPECT_LE(s.step_A, base.step_A);
  EXPECT_NO_THROW(s.validate());
  // the expected depth is clamped to the displacement limit (the ramp turns round there)
  EXPECT_NEAR(palp::settings_for_max_force(base, 5.0, 9e-3).stop_A,
              0.5 + (5.0 + 43.9 * 5e-3) / 2.918, 1e-12);
}

// firmware/core/README.md: a 3 A hold trips the default model (2 A, 60 A^2 s, 120 s) at 12.643 s.
// A two-level "ramp" 0 A -> 3 A, a minute at 0 A between repetitions (the model cools to 0).
TEST(ForceLimit, I2tPeakOfAThreeAmpHoldReachesTheTripLevelAtTheFirmwaresTime) {
  IndentationSettings hold;
  hold.start_A = 0.0;
  hold.stop_A = hold.step_A = 3.0;
  hold.unload = false;
  hold.repetitions = 1;
  hold.settle_s = 60;
  hold.dwell_s = -120 * std::log(1 - 60.0 / (120 * (9 - 4)));
  EXPECT_NEAR(hold.dwell_s, 12.643, 1e-3);
  EXPECT_NEAR(palp::ramp_i2t_peak_A2s(hold, CoilLimits{}), 60.0, 1e-9);
}

TEST(ForceLimit, ANineNewtonAskIsRefusedNamingTheClampAndTheLargestForce) {
  const IndentationSettings s = IndentationSettings::preset(IndentationPreset::two_d);
  EXPECT_EQ(refusal(s, 9.0),
            "max_force_N 9 N needs up to 3.660 A at the ramp's top (I_c 0.5 A + (9 N + k_v 43.9 "
            "N/m x 5 mm displacement limit) / K_f 2.918 N/A), above the coil's current clamp 3.2 "
            "A: at most 7.65 N");  // 7.659 N, rounded down
  EXPECT_EQ(refusal(s, 7.65), "accepted");
  EXPECT_EQ(refusal(s, 7.65, CoilLimits{.current_clamp_A = 3.0}).substr(0, 47),
            "max_force_N 7.65 N needs up to 3.197 A at the r");
}

TEST(ForceLimit, ALongOneDRampAtTheClampIsRefusedByTheI2tModel) {
  const IndentationSettings s = IndentationSettings::preset(IndentationPreset::one_d);
  const std::string why = refusal(s, 7.5);
  EXPECT_NE(why.find("heats the coil's I2t model to"), std::string::npos) << why;
  EXPECT_NE(why.find("above 80 % of its 60 A^2 s trip level (continuous 2 A, tau 120 s)"),
            std::string::npos)
      << why;
  // the 2D protocol (25 ms steps, 3 repetitions) carries the same force
  EXPECT_EQ(refusal(IndentationSettings::preset(IndentationPreset::two_d), 7.5), "accepted");
}

TEST(ForceLimit, NonPositiveForcesAndRampsWithoutADisplacementLimitAreRefused) {
  IndentationSettings s = IndentationSettings::preset(IndentationPreset::two_d);
  EXPECT_EQ(refusal(s, 0.0), "max_force_N must be a positive force, not 0 N");
  EXPECT_EQ(refusal(s, std::nan("")), "max_force_N must be a positive force, not nan N");
  s.displacement_limit_m = 0;
  EXPECT_EQ(refusal(s, 3.0),
            "max_force_N needs the ramp's displacement limit (displacement_limit_m is 0): it "
            "bounds the depth, and so the top current, a force needs");
}

}  // namespace force_limit_test
