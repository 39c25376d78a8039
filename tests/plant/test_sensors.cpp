// SPDX-License-Identifier: Apache-2.0
// Sensors: encoder quantisation, ADC transfer functions, noise spread, and repeatability: the
// same seed gives the same run, whatever else is read.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "palp/plant/noise.hpp"
#include "palp/plant/plant.hpp"
#include "palp/plant/sensors.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

TEST(Encoder, CountsWholeMicrometresFromTheStrokeOrigin) {
  Plant p{PlantConfig{}};
  p.reset_state({12.3456e-3, 0.0, 0.0});
  EXPECT_EQ(p.encoder_count(), 12346);
  p.reset_state({12.3454e-3, 0.0, 0.0});
  EXPECT_EQ(p.encoder_count(), 12345);
  p.reset_state({0.0, 0.0, 0.0});
  EXPECT_EQ(p.encoder_count(), 0);
}

TEST(PressureAdc, TransferIsHalfScalePlusFortyPercentPerFullScale) {
  EXPECT_EQ(pressure_code_from_Pa(0.0), 2048);
  EXPECT_EQ(pressure_code_from_Pa(1245.42), 3686);  // 0.9 x 4096 = 3686.4
  EXPECT_EQ(pressure_code_from_Pa(-1245.42), 410);  // 0.1 x 4096 = 409.6
  EXPECT_EQ(pressure_code_from_Pa(1e6), 4095);      // clamped
  EXPECT_EQ(pressure_code_from_Pa(-1e6), 0);
  EXPECT_NEAR(pressure_Pa_from_code(pressure_code_from_Pa(573.0)), 573.0, 0.4);
}

TEST(PressureAdc, ChannelsWithoutAPhantomReadAmbient) {
  PlantConfig cfg;
  cfg.sensors.pressure_noise_Pa = 0.0;
  Plant p{cfg};
  for (int ch = 1; ch <= 6; ++ch) EXPECT_EQ(p.pressure_adc(ch), 2048);
  EXPECT_THROW(p.pressure_adc(0), std::out_of_range);
  EXPECT_THROW(p.pressure_adc(7), std::out_of_range);
}

TEST(CurrentSense, CodeIsMidScaleAtZeroAndRoundTrips) {
  EXPECT_EQ(current_code_from_A(0.0), 2048);
  EXPECT_EQ(current_code_from_A(5.0), 4095);
  EXPECT_NEAR(current_A_from_code(current_code_from_A(1.0)), 1.0, 5.0 / 2048);
}

TEST(CurrentSense, HalfwayCodesRoundToEvenAsNearbyintDoes) {
  // 2048 + i / 5 A * 2048 lands exactly halfway for i = 5 / 4096 A and 15 / 4096 A
  EXPECT_EQ(current_code_from_A(5.0 / 4096), 2048);
  EXPECT_EQ(current_code_from_A(15.0 / 4096), 2050);
  EXPECT_EQ(current_code_from_A(-5.0 / 4096), 2048);
  EXPECT_EQ(current_code_from_A(-15.0 / 4096), 2046);
  EXPECT_EQ(current_code_from_A(1e300), 4095);  // far beyond 2^52: clamped
  EXPECT_EQ(current_code_from_A(-1e300), 0);
  EXPECT_EQ(current_code_from_A(std::numeric_limits<double>::infinity()), 4095);
}

TEST(CurrentSense, NoiseHasTheConfiguredSpreadAroundTheTrueCurrent) {
  Plant p{PlantConfig{}};  // parked, 0 A, nothing moves
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    p.step(0.0);
    const double i = p.current_sense_A();
    sum += i;
    sum2 += i * i;
  }
  const double mean = sum / n;
  const double rms = std::sqrt(sum2 / n - mean * mean);
  const double lsb = 10.0 / 4096.0;
  EXPECT_NEAR(mean, 0.0, 1e-4);
  EXPECT_NEAR(rms, std::sqrt(2e-3 * 2e-3 + lsb * lsb / 12.0), 0.05 * 2e-3);
}

// The plant's readings are the sensors' transfer functions applied to their streams' deviates:
// every code of a pad run in contact against gaussian(seed, stream, tick) itself.
TEST(Noise, ReadingsAreTheTransferOfTheirStreamsDeviates) {
  PlantConfig cfg;
  cfg.noise_seed = 11;
  cfg.sensors.encoder_noise_m = 0.3e-6;  // the encoder's optional jitter too
  test::Rig rig{cfg, load_shipped_phantom("pad_2d")};
  const ProbeSite site = rig.plant.phantom()->grid_point(8, 8);
  test::touch_at_float(rig, site.x_m, site.y_m);
  const SensorConfig& s = rig.plant.config().sensors;
  int pressure_off_centre = 0;
  for (int k = 0; k < 20000; ++k) {
    rig.tick(1.0 + 0.5 * std::sin(k * 1e-3));
    const std::uint64_t t = rig.plant.tick();
    const auto codes = rig.plant.pressure_adcs();
    for (int ch = 1; ch <= 6; ++ch) {
      const double p = rig.plant.channel_pressure_Pa(ch) +
                       s.pressure_noise_Pa * gaussian(11, 16 + static_cast<std::uint32_t>(ch), t);
      const std::uint16_t want = pressure_code_from_Pa(p, s.pressure_full_scale_Pa, s.pressure_adc_bits);
      ASSERT_EQ(codes[static_cast<std::size_t>(ch - 1)], want) << "tick " << t << " channel " << ch;
      ASSERT_EQ(rig.plant.pressure_adc(ch), want) << "tick " << t << " channel " << ch;
      pressure_off_centre += want != 2048;
    }
    const double i = rig.plant.coil_current_A() + s.current_sense_noise_A * gaussian(11, 1, t);
    ASSERT_EQ(rig.plant.current_sense_code(),
              current_code_from_A(i, s.current_sense_full_scale_A, s.current_sense_bits))
        << "tick " << t;
    const double pos = rig.plant.position_m() + s.encoder_noise_m * gaussian(11, 2, t);
    ASSERT_EQ(rig.plant.encoder_count(),
              static_cast<std::int32_t>(std::floor(pos / s.encoder_resolution_m + 0.5)))
        << "tick " << t;
  }
  EXPECT_GT(pressure_off_centre, 20000 * 6 / 2);  // the channels really carried pressure
}

std::vector<int> run_pad(std::uint64_t seed, bool read_extra) {
  PlantConfig cfg;
  cfg.noise_seed = seed;
  test::Rig rig{cfg, load_shipped_phantom("pad_2d")};
  const ProbeSite s = rig.plant.phantom()->grid_point(8, 8);
  test::touch_at_float(rig, s.x_m, s.y_m);
  std::vector<int> trace;
  for (int k = 0; k < 2000; ++k) {
    rig.tick(0.5 + k * 1e-3);
    if (read_extra) (void)rig.plant.pressure_adc(3);
    trace.push_back(rig.plant.encoder_count());
    trace.push_back(rig.plant.current_sense_code());
    trace.push_back(rig.plant.pressure_adc(6));
    trace.push_back(rig.plant.pressure_adc(6));  // a second read in the same tick: same sample
  }
  return trace;
}

TEST(Repeatability, SameSeedGivesTheSameRunWhateverElseIsRead) {
  const auto a = run_pad(7, false);
  EXPECT_EQ(a, run_pad(7, false));
  EXPECT_EQ(a, run_pad(7, true));
  EXPECT_NE(a, run_pad(8, false));
  for (std::size_t k = 0; k < a.size(); k += 4) EXPECT_EQ(a[k + 2], a[k + 3]);
}

}  // namespace
}  // namespace palp::plant
