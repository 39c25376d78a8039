// Contact laws: the exact sphere against Hertz (analysis-notes ratios), derivatives, the paper's
// operating-point arithmetic, the thickness factor.
#include <gtest/gtest.h>

#include <cmath>

#include "palp/analysis/contact_models.hpp"

using namespace palp::analysis;

namespace {
constexpr double R = 2.5e-3;
constexpr double Es = 137.6e3;
}  // namespace

TEST(AnalysisContactModels, SneddonOverHertzMatchesTheNotesRatios) {
  const double ratios[][2] = {{0.04, 0.996}, {0.17, 0.983}, {0.42, 0.958},
                              {0.88, 0.912}, {1.33, 0.868}, {1.74, 0.828}};
  for (const auto& rr : ratios) {
    const double d = rr[0] * R;
    EXPECT_NEAR(sneddon_force_N(d, Es, R) / hertz_force_N(d, Es, R), rr[1], 0.0011) << "delta/R " << rr[0];
  }
}

TEST(AnalysisContactModels, SneddonContactRadiusSolvesTheDepthEquationAndStaysBelowR) {
  for (double dr : {1e-9, 1e-6, 1e-3, 0.04, 0.5, 1.0, 1.74, 5.0, 10.0}) {
    const double a = sneddon_contact_radius_m(dr * R, R);
    ASSERT_GT(a, 0.0);
    ASSERT_LT(a, R);
    EXPECT_NEAR(a * std::atanh(a / R) / (dr * R), 1.0, 1e-8) << "delta/R " << dr;
  }
  EXPECT_EQ(sneddon_contact_radius_m(0.0, R), 0.0);
  EXPECT_EQ(sneddon_force_N(-1e-3, Es, R), 0.0);
}

TEST(AnalysisContactModels, SneddonSmallDepthEqualsHertzWithoutCancellation) {
  const double d = 1e-9;
  EXPECT_NEAR(sneddon_force_N(d, Es, R) / hertz_force_N(d, Es, R), 1.0, 1e-6);
}

TEST(AnalysisContactModels, AnalyticStiffnessEqualsNumericalDerivative) {
  for (double d : {0.1e-3, 1e-3, 2.935e-3, 4e-3}) {
    const double h = 1e-9;
    const double num_h = (hertz_force_N(d + h, Es, R) - hertz_force_N(d - h, Es, R)) / (2 * h);
    const double num_s = (sneddon_force_N(d + h, Es, R) - sneddon_force_N(d - h, Es, R)) / (2 * h);
    EXPECT_NEAR(hertz_stiffness_N_per_m(d, Es, R) / num_h, 1.0, 1e-6);
    EXPECT_NEAR(sneddon_stiffness_N_per_m(d, Es, R) / num_s, 1.0, 1e-6);
    const Thickness t{10e-3, Bonding::bonded};
    const double num_f = (thickness_factor(d + h, R, t) - thickness_factor(d - h, R, t)) / (2 * h);
    EXPECT_NEAR(thickness_factor_derivative_per_m(d, R, t) / num_f, 1.0, 1e-5);
  }
}

TEST(AnalysisContactModels, PaperSolidHertzTangentAtOperatingDepthGivesTheBiasForce) {
  // 0.74555 N/mm x 2.935 mm / 1.5 = 1.459 N: the Hertz curve with that tangent at 2.935 mm.
  const double k = 745.55, d0 = 2.935e-3;
  const double Estar = k / (2.0 * std::sqrt(R * d0));
  EXPECT_NEAR(hertz_stiffness_N_per_m(d0, Estar, R), k, 1e-9);
  EXPECT_NEAR(hertz_force_N(d0, Estar, R), 1.459, 0.0005);
  EXPECT_NEAR(hertz_force_N(d0, Estar, R), k * d0 / 1.5, 1e-12);
}

TEST(AnalysisContactModels, ThicknessFactorOnTenMillimetrePhantomIsOnePointTwoToOnePointFive) {
  const Thickness t{10e-3, Bonding::bonded};
  EXPECT_NEAR(thickness_factor(1e-3, R, t), 1.2, 0.03);
  EXPECT_NEAR(thickness_factor(4e-3, R, t), 1.5, 0.05);
  EXPECT_LT(thickness_factor(4e-3, R, {10e-3, Bonding::unbonded}), thickness_factor(4e-3, R, t));
  EXPECT_EQ(thickness_factor(0.0, R, t), 1.0);
}

TEST(AnalysisContactModels, ModulusConversionUsesPoisson) {
  EXPECT_NEAR(effective_modulus_Pa(1.59e6, 0.5), 2.12e6, 1.0);
  EXPECT_NEAR(youngs_modulus_Pa(effective_modulus_Pa(1.0e6, 0.3), 0.3), 1.0e6, 1e-6);
}
