// SPDX-License-Identifier: Apache-2.0
// From a second-order fit to the paper's quantities: the paper's own numbers (analysis-notes.md
// "Paper cross-checks"), the moduli of a synthetic contact of known k', k'', the Sneddon contact
// radius at the paper's operating points, and the refusals with their text.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "palp/analysis/contact_models.hpp"
#include "palp/analysis/dynamics.hpp"
#include "palp/error.hpp"

namespace {

namespace an = palp::analysis;
using cd = std::complex<double>;

template <class F>
std::string config_error_of(F&& f) {
  try {
    f();
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FreeAirFrom, ThePapersFreeAirValuesGiveItsMassAndDamping) {
  const an::FreeAirResult r = an::free_air_from(16.5192, 0.2595, 43.9);
  EXPECT_NEAR(r.m_v_kg, 0.1609, 0.00005);
  EXPECT_NEAR(r.b_v_N_s_per_m, 1.379, 0.0005);
  EXPECT_EQ(r.m_v_kg_se, 0.0);
  EXPECT_EQ(r.b_v_N_s_per_m_se, 0.0);
}

TEST(FreeAirFrom, StandardErrorsByTheDeltaMethod) {
  // 1 % on omega_n: 2 % on m_v; 1 % on omega_n and 2 % on zeta: sqrt(5) % on b_v
  const an::FreeAirResult r = an::free_air_from(16.5192, 0.2595, 43.9, 0.165192, 0.00519);
  EXPECT_NEAR(r.m_v_kg_se / r.m_v_kg, 0.02, 1e-12);
  EXPECT_NEAR(r.b_v_N_s_per_m_se / r.b_v_N_s_per_m, std::sqrt(5.0) * 0.01, 1e-12);
}

TEST(FreeAirFrom, RefusesNonPositiveInputs) {
  EXPECT_EQ(config_error_of([] { an::free_air_from(0.0, 0.26, 43.9); }),
            "free_air_from: omega_n must be positive (got 0 rad/s)");
  EXPECT_EQ(config_error_of([] { an::free_air_from(16.5, -0.1, 43.9); }),
            "free_air_from: zeta must be positive (got -0.1)");
  EXPECT_EQ(config_error_of([] { an::free_air_from(16.5, 0.26, 43.9, -1.0); }),
            "free_air_from: the standard error of omega_n must not be negative (got -1)");
}

TEST(Decompose, ThePapersSolidContactGivesItsEffectiveMassAndObjectDamping) {
  an::SecondOrderFit fit;
  fit.omega_n_rad_per_s = 66.31;
  fit.zeta = 3.00 * 66.31 / (2.0 * 789.5);  // the zeta that gives b_total = 3.00 N s/m
  const an::Decomposition d = an::decompose(fit, 745.6, an::InstrumentDynamics{});
  EXPECT_NEAR(d.k_eff_N_per_m, 789.5, 1e-9);
  EXPECT_NEAR(d.m_eff_kg, 0.1796, 0.00005);
  EXPECT_NEAR(d.b_total_N_s_per_m, 3.00, 1e-9);
  EXPECT_NEAR(d.b_o_N_s_per_m, 1.62, 0.005);
  EXPECT_NEAR(d.m_o_kg, 0.1796 - 0.1609, 0.00005);
}

TEST(Decompose, StandardErrorsCombineTheFitAndKo) {
  an::SecondOrderFit fit;
  fit.omega_n_rad_per_s = 66.31;
  fit.omega_n_rad_per_s_se = 0.6631;  // 1 %
  fit.zeta = 0.126;
  fit.zeta_se = 0.00252;  // 2 %
  const an::Decomposition d = an::decompose(fit, 745.6, an::InstrumentDynamics{}, 0.03 * 789.5);
  EXPECT_NEAR(d.m_eff_kg_se / d.m_eff_kg, std::sqrt(0.03 * 0.03 + 0.02 * 0.02), 1e-12);
  EXPECT_NEAR(d.b_total_N_s_per_m_se / d.b_total_N_s_per_m,
              std::sqrt(0.03 * 0.03 + 0.02 * 0.02 + 0.01 * 0.01), 1e-12);
  EXPECT_EQ(d.b_o_N_s_per_m_se, d.b_total_N_s_per_m_se);
}

TEST(Decompose, RefusesANonPositiveKoOrAFitWithoutOmegaN) {
  an::SecondOrderFit fit;
  fit.omega_n_rad_per_s = 66.31;
  fit.zeta = 0.126;
  EXPECT_EQ(config_error_of([&] { an::decompose(fit, 0.0, {}); }),
            "decompose: k_o must be positive (got 0 N/m)");
  EXPECT_EQ(config_error_of([] { an::decompose(an::SecondOrderFit{}, 745.6, {}); }),
            "decompose: the fit's omega_n must be positive (got 0 rad/s)");
}

TEST(ViscoelasticFrom, ReturnsTheComplexStiffnessOfASyntheticContactExactly) {
  const an::InstrumentDynamics inst;  // the paper's m_v, b_v, k_v
  std::vector<an::FrfLine> lines;
  const auto k_storage = [](double f) { return 700.0 + 5.0 * f; };
  const auto k_loss = [](double f) { return 60.0 + 2.0 * f; };
  for (double f : {2.0, 5.5, 11.0, 20.0}) {
    const double w = 2.0 * std::numbers::pi * f;
    const cd D(inst.k_v_N_per_m - inst.m_v_kg * w * w + k_storage(f),
               inst.b_v_N_s_per_m * w + k_loss(f));
    an::FrfLine l;
    l.f_Hz = f;
    l.G_m_per_N = 1.0 / D;
    lines.push_back(l);
  }
  const an::Viscoelastic v = an::viscoelastic_from(lines, inst, 1.0e-3, 2.5e-3);
  const double a = an::sneddon_contact_radius_m(1.0e-3, 2.5e-3);
  EXPECT_EQ(v.contact_radius_m, a);
  EXPECT_FALSE(v.flagged);  // 1 mm < R / 2
  EXPECT_TRUE(v.flag_reason.empty());
  ASSERT_EQ(v.lines.size(), 4u);
  for (const an::ViscoelasticLine& l : v.lines) {
    EXPECT_NEAR(l.k_storage_N_per_m, k_storage(l.f_Hz), 1e-9 * k_storage(l.f_Hz));
    EXPECT_NEAR(l.k_loss_N_per_m, k_loss(l.f_Hz), 1e-9 * k_storage(l.f_Hz));
    EXPECT_NEAR(l.E_storage_Pa, k_storage(l.f_Hz) / (2.0 * a), 1e-9 * l.E_storage_Pa);
    EXPECT_NEAR(l.E_loss_Pa, k_loss(l.f_Hz) / (2.0 * a), 1e-9 * l.E_storage_Pa);
    EXPECT_NEAR(l.tan_delta, k_loss(l.f_Hz) / k_storage(l.f_Hz), 1e-9);
  }
}

TEST(ViscoelasticFrom, ThePapersOperatingPointsGiveItsContactRadiiAndAreFlagged) {
  const an::FrfLine line{10.0, cd(1e-3, -1e-4), 0, {}, {}, 0};
  const double delta0_mm[] = {2.314, 2.935, 4.49};  // insert, solid, hollow
  const double a_mm[] = {2.03, 2.18, 2.39};
  for (int k = 0; k < 3; ++k) {
    const an::Viscoelastic v = an::viscoelastic_from({&line, 1}, {}, delta0_mm[k] * 1e-3, 2.5e-3);
    EXPECT_NEAR(v.contact_radius_m * 1e3, a_mm[k], 0.005);
    EXPECT_LT(v.contact_radius_m, 2.5e-3);
    EXPECT_TRUE(v.flagged);
  }
  const an::Viscoelastic v = an::viscoelastic_from({&line, 1}, {}, 2.935e-3, 2.5e-3);
  EXPECT_EQ(v.flag_reason,
            "delta0 = 2.935 mm is more than half the tip radius (2.5 mm): the moduli rest on the "
            "contact radius of a deep indentation (a = 2.18217 mm from the Sneddon sphere)");
}

TEST(ViscoelasticFrom, RefusesBadDepthRadiusOrAZeroResponse) {
  const an::FrfLine zero{10.0, cd(0, 0), 0, {}, {}, 0};
  EXPECT_EQ(config_error_of([&] { an::viscoelastic_from({&zero, 1}, {}, 1e-3, 2.5e-3); }),
            "viscoelastic_from: line 1 (f_Hz 10) has G = 0");
  EXPECT_EQ(config_error_of([&] { an::viscoelastic_from({}, {}, 0.0, 2.5e-3); }),
            "viscoelastic_from: delta0 must be positive (got 0 m)");
  EXPECT_EQ(config_error_of([&] { an::viscoelastic_from({}, {}, 1e-3, -1.0); }),
            "viscoelastic_from: the tip radius must be positive (got -1 m)");
}

}  // namespace
