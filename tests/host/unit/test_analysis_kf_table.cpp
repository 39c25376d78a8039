// SPDX-License-Identifier: Apache-2.0
// The K_f(stroke) table (IndentationParams::kf_table_*): interpolation, a fit on a curve made with
// a sloped K_f, and taking the table from a recording's sidecar only with its stroke origin.
#include <gtest/gtest.h>

#include <cmath>

#include "palp/analysis/indentation.hpp"
#include "palp/error.hpp"
#include "palp/indent.hpp"

namespace {

namespace an = palp::analysis;

an::IndentationParams with_table() {
  an::IndentationParams p;
  p.kf_table_stroke_m = {0.0, 0.017, 0.0235};
  p.kf_table_N_per_A = {3.30, 3.84, 2.918};
  p.stroke_origin_z_m = 0.001;  // the recording's z of the stroke origin
  return p;
}

TEST(KfTable, InterpolatesFromTheStrokeOriginAndHoldsTheEndValues) {
  const an::IndentationParams p = with_table();
  EXPECT_DOUBLE_EQ(p.force_constant_at(0.001), 3.30);
  EXPECT_NEAR(p.force_constant_at(0.001 + 0.0085), 3.57, 1e-12);
  EXPECT_DOUBLE_EQ(p.force_constant_at(-0.5), 3.30);
  EXPECT_DOUBLE_EQ(p.force_constant_at(0.5), 2.918);
  EXPECT_DOUBLE_EQ(an::IndentationParams{}.force_constant_at(0.01), 2.918);  // no table: constant
}

// A Hertz object (E* = 1 MPa) touched at 10 mm of stroke, where K_f climbs 0.032 N/A per mm:
// K_f(z) (i - I_c) = k_v delta + 4/3 E* sqrt(R) delta^1.5, z = z_c + delta.
an::Curve curve_with_sloped_kf(const an::IndentationParams& truth, double zc) {
  std::vector<double> z, i;
  for (int s = 0; s <= 250; ++s) {
    const double I = 0.5 + 0.01 * s;
    double d = 0;
    for (int it = 0; it < 60; ++it) {
      const double kf = truth.force_constant_at(zc + d);
      const double f = kf * (I - 0.5) - 43.9 * d - 4.0 / 3.0 * 1e6 * std::sqrt(2.5e-3) * d * std::sqrt(d);
      const double df = 43.9 + 2.0 * 1e6 * std::sqrt(2.5e-3 * d) + 1e-9;
      d = std::max(0.0, d + f / df);
    }
    for (int k = 0; k < 10; ++k) z.push_back(zc + d), i.push_back(I);
  }
  an::Curve c;
  c.z_m = Eigen::Map<Eigen::VectorXd>(z.data(), static_cast<Eigen::Index>(z.size()));
  c.i_A = Eigen::Map<Eigen::VectorXd>(i.data(), static_cast<Eigen::Index>(i.size()));
  return c;
}

TEST(KfTable, TheHertzFitWithTheTableRecoversEStarWhereTheConstantIsBiased) {
  const an::IndentationParams table = with_table();
  const double zc = 0.001 + 0.010;
  const an::Curve c = curve_with_sloped_kf(table, zc);
  const an::ModelFit right = an::fit_hertz(c, table);
  const an::ModelFit constant = an::fit_hertz(c, an::IndentationParams{});
  ASSERT_TRUE(right.Estar_Pa && constant.Estar_Pa);
  EXPECT_NEAR(*right.Estar_Pa, 1e6, 0.01e6);
  EXPECT_NEAR(right.contact_z_m, zc, 5e-6);
  EXPECT_GT(std::abs(*constant.Estar_Pa - 1e6), 0.10e6);  // K_f 2.918 against ~3.6 there
}

TEST(KfTable, TheSidecarsTableIsTakenOnlyWithItsStrokeOrigin) {
  palp::Sidecar side;
  side.calibration = {{"kf_table", {{{"position_mm", 0.0}, {"kf_N_per_A", 3.3}},
                                    {{"position_mm", 23.5}, {"kf_N_per_A", 2.918}}}}};
  side.stroke_origin_z_mm_reason = "the device's stroke origin is not homed (palpctl calibrate home)";
  an::IndentationParams p;
  try {
    palp::use_kf_table_of(side, p);
    FAIL() << "a table without a stroke origin was taken";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "the K_f(stroke) table needs the stroke origin, and the sidecar gives none (the "
                 "device's stroke origin is not homed (palpctl calibrate home)): analyse with the "
                 "constant K_f");
  }
  EXPECT_TRUE(p.kf_table_stroke_m.empty());
  side.stroke_origin_z_mm = 1.5;
  palp::use_kf_table_of(side, p);
  EXPECT_EQ(p.kf_table_stroke_m, (std::vector<double>{0.0, 0.0235}));
  EXPECT_DOUBLE_EQ(p.stroke_origin_z_m, 1.5e-3);
  EXPECT_DOUBLE_EQ(p.force_constant_at(1.5e-3), 3.3);
}

}  // namespace
