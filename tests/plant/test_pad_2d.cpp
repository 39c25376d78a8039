// SPDX-License-Identifier: Apache-2.0
// The 2D pad (§V): channel volumes, the row 8 / column 8 pressure rise on a ramp to 3 A, linear
// pressure-force behaviour, and the stiffness map (columns 2, 5, 8 softer; deep rows faint).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "palp/plant/pad_phantom.hpp"
#include "palp/plant/plant.hpp"
#include "palp/plant/sensors.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

using test::kR;

const PadPhantom& pad() {
  static const auto ph = load_shipped_phantom("pad_2d");
  return dynamic_cast<const PadPhantom&>(*ph);
}

// Paper §V-C: k = (F_o(0.75 mm) - F_o(0.25 mm)) / 0.5 mm, here from the pad's contact law.
double k_fd_law(int row, int column) {
  const ProbeSite s = pad().grid_point(row, column);
  const ContactParams p = pad().contact_params(s.x_m, s.y_m);
  return (elastic_contact(p, kR, 0.75e-3).force_N - elastic_contact(p, kR, 0.25e-3).force_N) /
         0.5e-3;
}

TEST(Pad, ChannelVolumesAreThePapersEnclosedVolumes) {
  for (int ch : {4, 5, 6}) EXPECT_NEAR(pad().channel_volume_m3(ch) * 1e9, 2757.0, 1.0);
  for (int ch : {1, 2, 3}) EXPECT_NEAR(pad().channel_volume_m3(ch) * 1e9, 2953.0, 1.0);
}

TEST(Pad, Row8Column8LiesOverShallowChannel6AndDeepChannel1) {
  const ProbeSite s = pad().grid_point(8, 8);
  EXPECT_NEAR(s.x_m, 0.080, 1e-12);
  EXPECT_NEAR(s.y_m, 0.075, 1e-12);
  EXPECT_NEAR(pad().channel_distance_m(6, s.x_m, s.y_m), 0.0, 1e-12);
  EXPECT_NEAR(pad().channel_distance_m(1, s.x_m, s.y_m), 0.0, 1e-12);
  EXPECT_NEAR(pad().channel_depth_below_surface_m(6, s.x_m, s.y_m), 0.005, 1e-12);
  EXPECT_GE(pad().channel_depth_below_surface_m(1, s.x_m, s.y_m) - 0.0025, 0.010);
}

// Ramp 0.5 -> 3 A by 0.01 A every 25 ms and back (§V-A), at row 8, column 8 (§V-D, Fig. 5c).
class PadRamp : public ::testing::Test {
 protected:
  struct Sample {
    double current_A, depth_m, force_N, p1_Pa, p6_Pa;
  };
  static void SetUpTestSuite() {
    test::Rig rig{PlantConfig{}, load_shipped_phantom("pad_2d")};
    const ProbeSite s = rig.plant.phantom()->grid_point(8, 8);
    test::touch_at_float(rig, s.x_m, s.y_m);
    rig.run(0.5, 0.2);
    const std::int32_t c0 = rig.plant.encoder_count();
    const auto n = static_cast<int>(std::lround(0.025 / rig.plant.config().tick_period_s));
    auto hold = [&](double i, std::vector<Sample>& out) {
      double d = 0, p1 = 0, p6 = 0;
      for (int t = 0; t < n; ++t) {
        rig.tick(i);
        d += (rig.plant.encoder_count() - c0) * 1e-6;
        p1 += pressure_Pa_from_code(rig.plant.pressure_adc(1));
        p6 += pressure_Pa_from_code(rig.plant.pressure_adc(6));
      }
      d /= n;
      out.push_back({i, d, test::kKf * (i - test::kIc) - test::kKv * d, p1 / n, p6 / n});
    };
    for (int k = 1; k <= 250; ++k) hold(0.5 + 0.01 * k, load_);
    for (int k = 249; k >= 0; --k) hold(0.5 + 0.01 * k, unload_);
  }
  static inline std::vector<Sample> load_, unload_;
};

TEST_F(PadRamp, ShallowChannel6RisesAbout573PaAndDeepChannel1About167Pa) {
  const Sample& top = load_.back();
  const Sample& rest = unload_.back();
  std::printf(
      "row 8, column 8 at 3 A: depth %.3f mm, F_o %.3f N, ch6 +%.1f Pa, ch1 +%.1f Pa, "
      "ratio %.2f\n",
      top.depth_m * 1e3, top.force_N, top.p6_Pa, top.p1_Pa, top.p6_Pa / top.p1_Pa);
  EXPECT_NEAR(top.p6_Pa, 573.0, 0.10 * 573.0);  // tolerance 10 %
  EXPECT_NEAR(top.p1_Pa, 167.0, 0.10 * 167.0);
  EXPECT_GE(top.p6_Pa / top.p1_Pa, 2.5);
  EXPECT_LE(top.p6_Pa / top.p1_Pa, 4.5);
  EXPECT_NEAR(top.depth_m, 3e-3, 0.15 * 3e-3);  // §V-D: "the measured 3 mm" displacement
  EXPECT_NEAR(rest.p6_Pa, 0.0, 5.0);            // back to ambient after unloading
}

TEST_F(PadRamp, ChannelPressuresRiseLinearlyWithForceWithoutHysteresis) {
  std::vector<double> f, p1, p6;
  for (const Sample& s : load_) {
    f.push_back(s.force_N);
    p1.push_back(s.p1_Pa);
    p6.push_back(s.p6_Pa);
  }
  const auto fit1 = test::fit_line(f, p1);
  const auto fit6 = test::fit_line(f, p6);
  std::printf("pressure vs force: ch6 R2 = %.5f, ch1 R2 = %.5f\n", fit6.r2, fit1.r2);
  EXPECT_GE(fit6.r2, 0.98);  // paper: 0.99665
  EXPECT_GE(fit1.r2, 0.98);  // paper: 0.98966
  // Same current on the way up and down: the pressure agrees within 3 % of the top value.
  for (std::size_t k = 0; k + 1 < load_.size(); ++k) {
    const Sample& up = load_[k];
    const Sample& down = unload_[load_.size() - 2 - k];
    ASSERT_NEAR(up.current_A, down.current_A, 1e-9);
    EXPECT_NEAR(up.p6_Pa, down.p6_Pa, 0.03 * load_.back().p6_Pa) << up.current_A;
  }
}

TEST_F(PadRamp, LinearModelFitsTheRampBetterThanHertz) {
  std::vector<test::StairPoint> pts;
  std::vector<double> d, f;
  for (const Sample& s : load_) {
    pts.push_back({s.current_A, s.depth_m, s.force_N});
    d.push_back(s.depth_m);
    f.push_back(s.force_N);
  }
  const double r2_lin = test::fit_line(d, f).r2;
  const double r2_hertz = test::fit_hertz(pts).r2;
  std::printf("pad ramp at row 8, column 8: R2 linear %.4f, Hertz %.4f\n", r2_lin, r2_hertz);
  EXPECT_GT(r2_lin, 0.99);      // paper Table I: 0.992-0.997
  EXPECT_GT(r2_lin, r2_hertz);  // paper Table I: Hertz 0.94-0.975
}

TEST(PadMap, ColumnsOverShallowChannelsAreAtLeast20PercentSofterThanNeighbours) {
  double weakest = 1.0;
  for (int r = 1; r <= 9; ++r) {
    for (int c : {2, 5, 8}) {
      const double contrast =
          1.0 - k_fd_law(r, c) / std::min(k_fd_law(r, c - 1), k_fd_law(r, c + 1));
      EXPECT_GE(contrast, 0.20) << "row " << r << ", column " << c;
      weakest = std::min(weakest, contrast);
    }
  }
  // Rows over the deep channels differ from their neighbours by less than half that contrast.
  for (int r : {2, 5, 8}) {
    for (int c : {1, 3, 4, 6, 7, 9}) {
      const double neighbours = 0.5 * (k_fd_law(r - 1, c) + k_fd_law(r + 1, c));
      EXPECT_LT(std::abs(1.0 - k_fd_law(r, c) / neighbours), 0.5 * weakest)
          << "row " << r << ", column " << c;
    }
  }
  std::printf("pad map: columns 2, 5, 8 at least %.0f %% softer (k_fd over 0.25-0.75 mm)\n",
              weakest * 100.0);
}

// The same contrast from simulated ramps (row 3, columns 7 and 8), as the paper measures it.
TEST(PadMap, SimulatedRampsShowTheShallowChannelUnderColumn8) {
  auto k_fd_sim = [](int column) {
    test::Rig rig{PlantConfig{}, load_shipped_phantom("pad_2d")};
    const ProbeSite s = rig.plant.phantom()->grid_point(3, column);
    test::touch_at_float(rig, s.x_m, s.y_m);
    rig.run(0.5, 0.2);
    const auto pts = test::staircase(rig, 0.5, 0.01, 0.025, 1.5, 1.5e-3, 0.025);
    auto force_at = [&](double depth) {
      for (std::size_t k = 1; k < pts.size(); ++k) {
        if (pts[k].depth_m >= depth) {
          const double w = (depth - pts[k - 1].depth_m) / (pts[k].depth_m - pts[k - 1].depth_m);
          return pts[k - 1].force_N + w * (pts[k].force_N - pts[k - 1].force_N);
        }
      }
      return std::numeric_limits<double>::quiet_NaN();
    };
    return (force_at(0.75e-3) - force_at(0.25e-3)) / 0.5e-3;
  };
  const double k7 = k_fd_sim(7), k8 = k_fd_sim(8);
  std::printf("row 3: k_fd column 7 = %.3f N/mm, column 8 = %.3f N/mm\n", k7 * 1e-3, k8 * 1e-3);
  EXPECT_LT(k8, 0.8 * k7);
  EXPECT_NEAR(k7, k_fd_law(3, 7), 0.05 * k_fd_law(3, 7));
  EXPECT_NEAR(k8, k_fd_law(3, 8), 0.05 * k_fd_law(3, 8));
}

}  // namespace
}  // namespace palp::plant
