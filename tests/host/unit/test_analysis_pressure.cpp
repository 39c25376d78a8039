// SPDX-License-Identifier: Apache-2.0
// Pressure analysis (palp/analysis/pressure.hpp): known answers. The paper's §V-D volumes and
// volume changes, hand-computed Boyle values, lines through synthetic noisy pressures, and the
// hysteresis of branches with a known gap.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "palp/analysis/pressure.hpp"
#include "palp/error.hpp"
#include "test_analysis_synth.hpp"

namespace palp::analysis {
namespace {

constexpr double kMm3 = 1e-9;  // m^3 per mm^3

template <class F>
std::string config_error_text(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

TEST(BoyleVolume, PaperChannelPlusTubeVolumesAre2757And2953Mm3) {
  ChannelGeometry shallow;  // defaults: the paper's Ø5 mm x 90 mm channel, 1/16 in x 50 cm tube
  ChannelGeometry deep;
  deep.channel_length_m = 100e-3;
  // pi/4 (5^2 x 90 + 1.5875^2 x 500) = pi/4 x 3510.078 mm^3, pi/4 x 3760.078 mm^3
  EXPECT_NEAR(enclosed_volume_m3(shallow) / kMm3, std::numbers::pi / 4 * 3510.078125, 1e-9);
  EXPECT_NEAR(enclosed_volume_m3(deep) / kMm3, std::numbers::pi / 4 * 3760.078125, 1e-9);
  EXPECT_NEAR(enclosed_volume_m3(shallow) / kMm3, 2757.0, 0.5);  // the paper's rounded values
  EXPECT_NEAR(enclosed_volume_m3(deep) / kMm3, 2953.0, 0.5);
  ChannelGeometry no_tube;
  no_tube.tube_length_m = 0.0;
  EXPECT_NEAR(enclosed_volume_m3(no_tube) / kMm3, std::numbers::pi / 4 * 2250.0, 1e-9);
}

TEST(BoyleVolume, PaperRisesOf573And167PaGive15_5And4_86Mm3) {
  // dV = V1 (1 - P1/P2) = V1 dP / (P1 + dP): 2757 x 573 / 101898 = 15.5034,
  // 2953 x 167 / 101492 = 4.8590 (the paper: 15.5 and 4.85, together 20.35 mm^3)
  const BoyleResult top = boyle_volume_change(2757 * kMm3, 573.0);
  const BoyleResult bottom = boyle_volume_change(2953 * kMm3, 167.0);
  EXPECT_NEAR(top.dV_isothermal_m3 / kMm3, 2757.0 * 573.0 / 101898.0, 1e-9);
  EXPECT_NEAR(bottom.dV_isothermal_m3 / kMm3, 2953.0 * 167.0 / 101492.0, 1e-9);
  EXPECT_NEAR(top.dV_isothermal_m3 / kMm3, 15.50, 0.01);
  EXPECT_NEAR(bottom.dV_isothermal_m3 / kMm3, 4.86, 0.01);
  EXPECT_NEAR((top.dV_isothermal_m3 + bottom.dV_isothermal_m3) / kMm3, 20.36, 0.01);
  EXPECT_DOUBLE_EQ(top.P1_Pa, 101325.0);
  EXPECT_DOUBLE_EQ(top.P2_Pa, 101898.0);
}

TEST(BoyleVolume, DoublingThePressureHalvesTheVolumeIsothermallyAndBy39PercentAdiabatically) {
  const BoyleResult b = boyle_volume_change(1000 * kMm3, 101325.0);
  EXPECT_NEAR(b.dV_isothermal_m3 / kMm3, 500.0, 1e-9);
  // 1000 (1 - 0.5^(1/1.4)) = 390.49 mm^3
  EXPECT_NEAR(b.dV_adiabatic_m3 / kMm3, 1000.0 * (1.0 - std::pow(0.5, 1.0 / 1.4)), 1e-9);
  EXPECT_NEAR(b.dV_adiabatic_m3 / kMm3, 390.49, 0.01);
  // small rises: the isothermal estimate is gamma = 1.4 times the adiabatic one
  const BoyleResult s = boyle_volume_change(2757 * kMm3, 573.0);
  EXPECT_NEAR(s.dV_isothermal_m3 / s.dV_adiabatic_m3, 1.4, 0.002);
  // a drop in pressure is an expansion: negative dV
  EXPECT_LT(boyle_volume_change(2757 * kMm3, -100.0).dV_isothermal_m3, 0.0);
  // no rise, no change (and +0, which prints as 0, not -0)
  const BoyleResult none = boyle_volume_change(2757 * kMm3, 0.0);
  EXPECT_EQ(none.dV_isothermal_m3, 0.0);
  EXPECT_FALSE(std::signbit(none.dV_adiabatic_m3));
  EXPECT_FALSE(std::signbit(none.dV_isothermal_m3));
}

TEST(BoyleVolume, BadGeometryOrPressureIsAConfigErrorNamingIt) {
  EXPECT_EQ(config_error_text([] { boyle_volume_change(0.0, 10.0); }),
            "enclosed volume must be a finite number above 0, got 0");
  EXPECT_EQ(config_error_text([] { boyle_volume_change(1e-6, -101325.0); }),
            "pressure change -101325 Pa takes the absolute pressure to 0 Pa (must stay above 0)");
  EXPECT_EQ(config_error_text([] { boyle_volume_change(1e-6, 10.0, -1.0); }),
            "ambient pressure must be a finite number above 0, got -1");
  ChannelGeometry g;
  g.channel_diameter_m = -5e-3;
  EXPECT_EQ(config_error_text([&] { enclosed_volume_m3(g); }),
            "channel diameter must be a finite number above 0, got -0.005");
  g = ChannelGeometry{};
  g.tube_length_m = std::nan("");
  EXPECT_EQ(config_error_text([&] { enclosed_volume_m3(g); }),
            "tube length must be a finite number of 0 or more, got nan");
}

TEST(PressureLine, ExactLineIsRecoveredExactlyWithR2One) {
  Eigen::VectorXd F = Eigen::VectorXd::LinSpaced(50, 0.0, 7.0);
  Eigen::VectorXd p = (78.5 * F.array() + 12.0).matrix();
  const LineFit f = fit_line(F, p);
  ASSERT_TRUE(f.slope && f.intercept && f.r2);
  EXPECT_NEAR(*f.slope.value, 78.5, 1e-10);
  EXPECT_NEAR(*f.intercept.value, 12.0, 1e-10);
  EXPECT_NEAR(*f.r2.value, 1.0, 1e-14);
  EXPECT_EQ(f.n, 50);
}

TEST(PressureLine, NoisyLineSlopeWithinThreeStandardErrorsAndR2AsExpected) {
  std::mt19937 rng(6);
  std::normal_distribution<double> noise(0.0, 5.0);  // 5 Pa rms on a 550 Pa rise
  const int n = 1000;
  Eigen::VectorXd F = Eigen::VectorXd::LinSpaced(n, 0.0, 7.0), p(n);
  for (int k = 0; k < n; ++k) p[k] = 78.5 * F[k] + 12.0 + noise(rng);
  const LineFit f = fit_line(F, p);
  ASSERT_TRUE(f.slope && f.slope_se && f.r2);
  EXPECT_LT(std::abs(*f.slope.value - 78.5), 3.0 * *f.slope_se.value);
  EXPECT_LT(std::abs(*f.slope.value - 78.5) / 78.5, 0.005);
  // expected R^2 = 1 - var(noise)/var(p) = 1 - 25 / (78.5^2 x 7^2 / 12) = 0.99901
  EXPECT_NEAR(*f.r2.value, 1.0 - 25.0 / (78.5 * 78.5 * 49.0 / 12.0), 2e-4);
  // the slope's s.e. is sigma / sqrt(sum dx^2) = 5 / sqrt(n x 49/12) = 0.0782
  EXPECT_NEAR(*f.slope_se.value, 5.0 / std::sqrt(n * 49.0 / 12.0), 0.01);
}

TEST(PressureLine, TooFewSamplesOrConstantForceIsAbsentWithTheReason) {
  const LineFit two = fit_line(Eigen::Vector2d(1, 2), Eigen::Vector2d(3, 4));
  EXPECT_FALSE(two.slope);
  EXPECT_EQ(two.slope.reason, "a line needs at least 3 samples, got 2");
  const LineFit flat = fit_line(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(3, 4, 5));
  EXPECT_FALSE(flat.r2);
  EXPECT_EQ(flat.r2.reason, "the force does not vary over the samples");
  EXPECT_EQ(config_error_text([] { fit_line(Eigen::Vector3d(1, 2, 3), Eigen::Vector2d(3, 4)); }),
            "fit_line: x has 3 values, y has 2");
}

TEST(PressureHysteresis, UnloadingTenPascalAboveLoadingGivesAreaAndRatio) {
  const Eigen::VectorXd Fl = Eigen::VectorXd::LinSpaced(101, 0.0, 5.0);
  const Eigen::VectorXd pl = 100.0 * Fl;
  const Eigen::VectorXd Fu = Eigen::VectorXd::LinSpaced(101, 5.0, 0.0);  // back down
  const Eigen::VectorXd pu = (100.0 * Fu.array() + 10.0).matrix();
  const PressureHysteresis h = pressure_hysteresis(Fl, pl, Fu, pu);
  ASSERT_TRUE(h.loop_area_Pa_N && h.ratio && h.max_gap_Pa);
  EXPECT_NEAR(*h.loop_area_Pa_N.value, 50.0, 1e-9);   // 10 Pa x 5 N
  EXPECT_NEAR(*h.ratio.value, 50.0 / (5.0 * 500.0), 1e-12);
  EXPECT_NEAR(*h.max_gap_Pa.value, 10.0, 1e-9);
  const PressureHysteresis none = pressure_hysteresis(Fl, pl, Fu, (100.0 * Fu).eval());
  EXPECT_NEAR(*none.ratio.value, 0.0, 1e-12);
  const PressureHysteresis no_unload = pressure_hysteresis(Fl, pl, Eigen::VectorXd(), Eigen::VectorXd());
  EXPECT_EQ(no_unload.ratio.reason, "the repetition has no unloading branch");
}

TEST(PressureAnalysis, SyntheticIndentationRecoversPerChannelSlopeRiseAndNoHysteresis) {
  test::SynthSpec s;
  s.object_force = [](double d) { return d > 0 ? 300.0 * d : 0.0; };  // 0.3 N/mm
  s.i_top_A = 1.5;
  s.i_step_A = 0.01;
  s.reps = 3;
  const Curve c = test::synth_curve(s);
  const IndentationParams& p = s.params;
  const Eigen::VectorXd Fo = object_force_N(c, p, s.contact_z_m);
  Eigen::MatrixXd P(c.z_m.size(), 2);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (Eigen::Index k = 0; k < P.rows(); ++k) {
    P(k, 0) = 20.0 + 57.0 * std::max(Fo[k], 0.0) + noise(rng);  // "deep": 57 Pa/N
    P(k, 1) = 195.0 * std::max(Fo[k], 0.0) + noise(rng);        // "shallow": 195 Pa/N
  }
  const PressureResult r = analyze_pressure(c, P, p, s.contact_z_m);
  ASSERT_EQ(r.channels.size(), 2u);
  EXPECT_EQ(r.channels[1].channel, 2);
  EXPECT_NEAR(*r.channels[0].fit.slope.value, 57.0, 57.0 * 0.01);
  EXPECT_NEAR(*r.channels[1].fit.slope.value, 195.0, 195.0 * 0.01);
  EXPECT_GT(*r.channels[1].fit.r2.value, 0.999);
  // rise: from the first contact sample (F_o = 0) to the peak F_o = K_f x 1 A - k_v delta_max
  const double Fmax = Fo.maxCoeff();
  EXPECT_NEAR(*r.channels[1].rise_Pa.value, 195.0 * Fmax, 6.0);
  ASSERT_EQ(r.channels[1].hysteresis.size(), 3u);
  EXPECT_LT(std::abs(*r.channels[1].hysteresis_ratio_mean.value), 0.01);
  EXPECT_EQ(r.n_loading, 3 * 101);
}

}  // namespace
}  // namespace palp::analysis
