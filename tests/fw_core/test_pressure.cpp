// SPDX-License-Identifier: Apache-2.0
// PressureChannels and the sensor calibration helpers (firmware/core/include/palp/fw/pressure.hpp).
//
// Known answers from the stated transfer p = (code - 2048) * 1245.42 / 1638.4 Pa
// (0.76014404296875 Pa per code), worked out by hand / independently:
//   2048 -> 0 Pa; 3686 -> 1245.11594 Pa; 410 -> -1245.11594 Pa; 2867 -> 622.55797 Pa;
//   4095 -> 1556.01486 Pa.
#include "palp/fw/pressure.hpp"

#include <gtest/gtest.h>

namespace palp::fw {
namespace {

PressureChannels::Codes all(std::uint16_t code) { return {code, code, code, code, code, code}; }

TEST(Pressure, NominalTransferGivesKnownPascalsForKnownCodes) {
  EXPECT_EQ(nominal_pressure_Pa(2048.0f), 0.0f);
  EXPECT_NEAR(nominal_pressure_Pa(3686.0f), 1245.11594f, 1e-3f);
  EXPECT_NEAR(nominal_pressure_Pa(410.0f), -1245.11594f, 1e-3f);
  EXPECT_NEAR(nominal_pressure_Pa(2867.0f), 622.55797f, 1e-3f);
  EXPECT_NEAR(nominal_pressure_Pa(4095.0f), 1556.01486f, 1e-3f);
  // the full scale lands on 10 % and 90 % of the 4096-code range
  EXPECT_NEAR(nominal_pressure_Pa(0.9f * 4096.0f), 1245.42f, 1e-3f);
  EXPECT_NEAR(nominal_pressure_Pa(0.1f * 4096.0f), -1245.42f, 1e-3f);
}

TEST(Pressure, ConstantCodeGivesTheExactPascalsOnEveryChannelOncePerWindow) {
  PressureChannels p(10);
  for (int tick = 1; tick <= 9; ++tick) EXPECT_FALSE(p.add(all(3686))) << tick;
  EXPECT_TRUE(p.add(all(3686)));
  for (std::size_t ch = 0; ch < kPressureChannelCount; ++ch) {
    EXPECT_EQ(p.mean_code()[ch], 3686.0f);
    EXPECT_NEAR(p.pressure_Pa()[ch], 1245.11594f, 1e-3f);
  }
  EXPECT_EQ(p.ticks_in_window(), 0);
}

TEST(Pressure, DecimationWindowIsTheExactMeanOfItsTicksPerChannel) {
  PressureChannels p(4);
  // channel c sees 2048 + c, 2049 + c, 2050 + c, 2051 + c: mean 2049.5 + c
  for (std::uint16_t k = 0; k < 4; ++k) {
    PressureChannels::Codes codes{};
    for (std::size_t ch = 0; ch < kPressureChannelCount; ++ch)
      codes[ch] = static_cast<std::uint16_t>(2048 + k + ch);
    EXPECT_EQ(p.add(codes), k == 3);
  }
  for (std::size_t ch = 0; ch < kPressureChannelCount; ++ch) {
    EXPECT_EQ(p.mean_code()[ch], 2049.5f + static_cast<float>(ch));
    EXPECT_NEAR(p.pressure_Pa()[ch], (1.5f + static_cast<float>(ch)) * 0.76014404f, 1e-5f);
  }
  // windows are back to back: the next output averages only the next 4 ticks
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(p.add(all(2048)));
  EXPECT_TRUE(p.add(all(2048)));
  EXPECT_EQ(p.pressure_Pa()[0], 0.0f);
}

TEST(Pressure, LongestWindowOf65535TicksAveragesWithoutOverflow) {
  // 32 768 ticks of 4095 and 32 767 of 0: sum 134 184 960 (beyond float's 2^24), mean
  // 2047.53124285 codes = -0.356323 Pa.
  PressureChannels p(65535);
  bool done = false;
  for (int k = 0; k < 65535; ++k) done = p.add(all(k % 2 == 0 ? 4095 : 0));
  ASSERT_TRUE(done);
  EXPECT_NEAR(p.mean_code()[3], 2047.531243f, 2e-4f);
  EXPECT_NEAR(p.pressure_Pa()[3], -0.356323f, 2e-4f);
}

TEST(Pressure, CalibrationSubtractsTheOffsetThenAppliesTheGainPerChannel) {
  PressureChannels p(1);
  PressureCalibration cal;
  cal.offset_Pa = {100.0f, 0.0f, -50.0f, 0.0f, 0.0f, 0.0f};
  cal.gain = {2.0f, 1.0f, 1.0f, 0.5f, 1.0f, 1.0f};
  p.set_calibration(cal);
  ASSERT_TRUE(p.add(all(2867)));  // nominal 622.55797 Pa
  EXPECT_NEAR(p.pressure_Pa()[0], 1045.11594f, 1e-3f);  // (622.558 - 100) * 2
  EXPECT_NEAR(p.pressure_Pa()[1], 622.55797f, 1e-3f);
  EXPECT_NEAR(p.pressure_Pa()[2], 672.55797f, 1e-3f);   // (622.558 + 50) * 1
  EXPECT_NEAR(p.pressure_Pa()[3], 311.27899f, 1e-3f);   // 622.558 * 0.5
  EXPECT_EQ(p.mean_code()[0], 2867.0f);                 // the raw mean stays uncalibrated
}

TEST(Pressure, CodesAbove4095AreClippedAndCounted) {
  PressureChannels p(2);
  PressureChannels::Codes codes = all(4095);
  codes[5] = 0xFFFF;
  EXPECT_FALSE(p.add(codes));
  EXPECT_TRUE(p.add(codes));
  EXPECT_EQ(p.mean_code()[5], 4095.0f);
  EXPECT_EQ(p.clipped_codes(), 2u);
}

TEST(Pressure, RestartDropsThePartialWindowAndZeroDecimationMeansOne) {
  PressureChannels p(3);
  EXPECT_FALSE(p.add(all(4000)));
  EXPECT_FALSE(p.add(all(4000)));
  p.restart();
  EXPECT_FALSE(p.add(all(2048)));
  EXPECT_FALSE(p.add(all(2048)));
  EXPECT_TRUE(p.add(all(2048)));
  EXPECT_EQ(p.mean_code()[0], 2048.0f);
  p.set_decimation(0);
  EXPECT_EQ(p.decimation(), 1);
  EXPECT_TRUE(p.add(all(2049)));
}

TEST(CurrentSense, CalibrationSubtractsTheOffsetThenAppliesTheGain) {
  EXPECT_FLOAT_EQ(apply_current_calibration(1.05f, 0.05f, 0.98f), 0.98f);
  EXPECT_FLOAT_EQ(apply_current_calibration(-0.5f, 0.1f, 2.0f), -1.2f);
  EXPECT_EQ(apply_current_calibration(0.25f, 0.0f, 1.0f), 0.25f);
}

}  // namespace
}  // namespace palp::fw
