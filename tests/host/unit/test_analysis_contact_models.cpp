// SPDX-License-Identifier: Apache-2.0
// Contact laws: the exact sphere against Hertz (analysis-notes ratios), derivatives, the paper's
// operating-point arithmetic, the thickness factor.
#include <gtest/gtest.h>

#include <cmath>

#include "palp/analysis/contact_models.hpp"

using namespace palp::analysis;

namespace {
constexpr double kTipR = 2.5e-3;
constexpr double Es = 137.6e3;
}  // namespace

TEST(AnalysisContactModels, SneddonOverHertzMatchesTheNotesRatios) {
  const double ratios[][2] = {{0.04, 0.996}, {0.17, 0.983}, {0.42, 0.958},
                              {0.88, 0.912}, {1.33, 0.868}, {1.74, 0.828}};
  for (const auto& rr : ratios) {
    const double d = rr[0] * kTipR;
    EXPECT_NEAR(sneddon_force_N(d, Es, kTipR) / hertz_force_N(d, Es, kTipR), rr[1], 0.0011) << "delta/R " << rr[0];
  }
}

TEST(AnalysisContactModels, SneddonContactRadiusSolvesTheDepthEquationAndStaysBelowR) {
  for (double dr : {1e-9, 1e-6, 1e-3, 0.04, 0.5, 1.0, 1.74, 5.0, 10.0}) {
    const double a = sneddon_contact_radius_m(dr * kTipR, kTipR);
    ASSERT_GT(a, 0.0);
    ASSERT_LT(a, kTipR);
    EXPECT_NEAR(a * std::atanh(a / kTipR) / (dr * kTipR), 1.0, 1e-8) << "delta/R " << dr;
  }
  EXPECT_EQ(sneddon_contact_radius_m(0.0, kTipR), 0.0);
  EXPECT_EQ(sneddon_force_N(-1e-3, Es, kTipR), 0.0);
}

TEST(AnalysisContactModels, SneddonSmallDepthEqualsHertzWithoutCancellation) {
  const double d = 1e-9;
  EXPECT_NEAR(sneddon_force_N(d, Es, kTipR) / hertz_force_N(d, Es, kTipR), 1.0, 1e-6);
}

TEST(AnalysisContactModels, AnalyticStiffnessEqualsNumericalDerivative) {
  for (double d : {0.1e-3, 1e-3, 2.935e-3, 4e-3}) {
    const double h = 1e-9;
    const double num_h = (hertz_force_N(d + h, Es, kTipR) - hertz_force_N(d - h, Es, kTipR)) / (2 * h);
    const double num_s = (sneddon_force_N(d + h, Es, kTipR) - sneddon_force_N(d - h, Es, kTipR)) / (2 * h);
    EXPECT_NEAR(hertz_stiffness_N_per_m(d, Es, kTipR) / num_h, 1.0, 1e-6);
    EXPECT_NEAR(sneddon_stiffness_N_per_m(d, Es, kTipR) / num_s, 1.0, 1e-6);
    const Thickness t{10e-3, Bonding::bonded};
    const double num_f = (thickness_factor(d + h, kTipR, t) - thickness_factor(d - h, kTipR, t)) / (2 * h);
    EXPECT_NEAR(thickness_factor_derivative_per_m(d, kTipR, t) / num_f, 1.0, 1e-5);
  }
}

TEST(AnalysisContactModels, PaperSolidHertzTangentAtOperatingDepthGivesTheBiasForce) {
  // 0.74555 N/mm x 2.935 mm / 1.5 = 1.459 N: the Hertz curve with that tangent at 2.935 mm.
  const double k = 745.55, d0 = 2.935e-3;
  const double Estar = k / (2.0 * std::sqrt(kTipR * d0));
  EXPECT_NEAR(hertz_stiffness_N_per_m(d0, Estar, kTipR), k, 1e-9);
  EXPECT_NEAR(hertz_force_N(d0, Estar, kTipR), 1.459, 0.0005);
  EXPECT_NEAR(hertz_force_N(d0, Estar, kTipR), k * d0 / 1.5, 1e-12);
}

TEST(AnalysisContactModels, ThicknessFactorOnTenMillimetrePhantomIsOnePointTwoToOnePointFive) {
  const Thickness t{10e-3, Bonding::bonded};
  EXPECT_NEAR(thickness_factor(1e-3, kTipR, t), 1.2, 0.03);
  EXPECT_NEAR(thickness_factor(4e-3, kTipR, t), 1.5, 0.05);
  EXPECT_LT(thickness_factor(4e-3, kTipR, {10e-3, Bonding::unbonded}), thickness_factor(4e-3, kTipR, t));
  EXPECT_EQ(thickness_factor(0.0, kTipR, t), 1.0);
}

TEST(AnalysisContactModels, ModulusConversionUsesPoisson) {
  EXPECT_NEAR(effective_modulus_Pa(1.59e6, 0.5), 2.12e6, 1.0);
  EXPECT_NEAR(youngs_modulus_Pa(effective_modulus_Pa(1.0e6, 0.3), 0.3), 1.0e6, 1e-6);
}
