// SPDX-License-Identifier: Apache-2.0
// The pad as a standard linear solid (issue 24, README.md "2D pad"): it relaxes to the tuned law,
// its linearisation's second order matches the exact dynamic stiffness at its resonance, and
// pad_2d_damping's inclusion changes the damping (retardation time) but not the stiffness.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <string>

#include "palp/plant/linearisation.hpp"
#include "palp/plant/pad_phantom.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

/// The shipped pad `name`, loaded once and kept for the test program's life.
const PadPhantom& pad(const std::string& name) {
  static std::map<std::string, std::shared_ptr<const Phantom>> loaded;
  auto& p = loaded[name];
  if (!p) p = load_shipped_phantom(name);
  return dynamic_cast<const PadPhantom&>(*p);
}

/// The plant at grid point (row, column) of `name`, the floating tip just touching.
Linearisation linearised_at(const char* name, int row, int column, double bias_A) {
  test::Rig rig{PlantConfig{}, load_shipped_phantom(name)};
  const ProbeSite s = rig.plant.phantom()->grid_point(row, column);
  test::touch_at_float(rig, s.x_m, s.y_m);
  return linearise(rig.plant, bias_A);
}

TEST(PadViscoelastic, EveryGridPointIsAStandardLinearSolidRelaxingInAThirdOfASecondBy20Percent) {
  for (const ProbeSite& s : pad("pad_2d").sites()) {
    const ContactParams p = pad("pad_2d").contact_params(s.x_m, s.y_m);
    ASSERT_EQ(p.viscoelasticity, Viscoelasticity::standard_linear_solid);
    EXPECT_EQ(p.sls_relaxation_time_s, 0.3);
    EXPECT_EQ(p.sls_strength, 0.2);
    EXPECT_EQ(p.retardation_time_s, 2e-3);  // the Kelvin-Voigt part stays
  }
}

TEST(PadViscoelastic, HeldDepthRelaxesFromOnePointTwoTimesToTheTunedLaw) {
  const ProbeSite s = pad("pad_2d").grid_point(5, 4);
  const ContactParams p = pad("pad_2d").contact_params(s.x_m, s.y_m);
  const double R = PlantConfig{}.mechanics.tip_radius_m, depth = 0.6e-3, dt = 50e-6;
  const double relaxed = elastic_contact(p, R, depth).force_N;
  ContactModel m;
  m.evaluate(p, R, 0.0, 0.0, dt);
  const double f0 = m.evaluate(p, R, depth, 0.0, dt).force_N;  // a step within one tick
  double f_tau = 0, f_end = 0;
  for (int k = 1; k <= 60000; ++k) {  // 3 s = 10 tau_1
    const double f = m.evaluate(p, R, depth, 0.0, dt).force_N;
    if (k == 6000) f_tau = f;         // tau_1 = 0.3 s after the step
    f_end = f;
  }
  EXPECT_NEAR(f0, 1.2 * relaxed, 1e-4 * relaxed);
  EXPECT_NEAR(f_tau, relaxed * (1 + 0.2 * std::exp(-1.0)), 1e-3 * relaxed);
  EXPECT_NEAR(f_end, relaxed, 1e-5 * relaxed);
}

TEST(PadViscoelastic, LinearisationIsTheExactDynamicStiffnessAtItsOwnNaturalFrequency) {
  for (const auto& [row, column] : {std::pair{5, 4}, std::pair{5, 5}, std::pair{8, 8}}) {
    const Linearisation l = linearised_at("pad_2d", row, column, 1.0);
    ASSERT_TRUE(l.in_contact);
    // the relaxing part: g_1 k_o with tau_1, the equilibrium on the relaxed law
    EXPECT_NEAR(l.k_relaxing_N_per_m, 0.2 * l.k_o_N_per_m, 1e-9 * l.k_o_N_per_m);
    EXPECT_EQ(l.relaxation_time_s, 0.3);
    // 1 / G at omega_n: real part + m w^2 is k, imaginary part / w is b (G is the exact one)
    const double w = l.omega_n_rad_per_s;
    const std::complex<double> d = 1.0 / l.G(w / (2 * std::numbers::pi));
    EXPECT_NEAR(d.real() + l.m_kg * w * w, l.k_N_per_m, 1e-9 * l.k_N_per_m);
    EXPECT_NEAR(d.imag() / w, l.b_N_s_per_m, 1e-9 * l.b_N_s_per_m);
    EXPECT_NEAR(w, std::sqrt(l.k_N_per_m / l.m_kg), 1e-12 * w);
    // w tau_1 >= 36.7: the relaxing part is nearly all stiffness, 1.2 k_o in all (row 5 meets
    // the oblique contact on a 12 degree flank of the waves: 36.7, from 37.0 before)
    EXPECT_GT(w * l.relaxation_time_s, 36.5);
    EXPECT_NEAR(l.k_sls_N_per_m, l.k_relaxing_N_per_m, 1e-3 * l.k_relaxing_N_per_m);
    EXPECT_LT(l.b_sls_N_s_per_m, 0.02 * l.b_N_s_per_m);
    std::printf("pad (%d, %d) at 1.0 A: k_o %.0f N/m, omega_n %.2f rad/s (%.2f Hz), zeta %.4f\n",
                row, column, l.k_o_N_per_m, w, w / (2 * std::numbers::pi), l.zeta);
  }
}

TEST(PadViscoelastic, KelvinVoigtPhantomsKeepTheirSecondOrderLinearisation) {
  test::Rig rig{PlantConfig{}, load_shipped_phantom("solid_1d")};
  const ProbeSite p3 = rig.plant.phantom()->position(3);
  test::touch_at_float(rig, p3.x_m, p3.y_m);
  const Linearisation l = linearise(rig.plant, 1.0);
  EXPECT_EQ(l.k_relaxing_N_per_m, 0.0);
  EXPECT_EQ(l.k_N_per_m, l.k_v_N_per_m + l.k_o_N_per_m + l.k_coil_N_per_m);
  EXPECT_EQ(l.b_N_s_per_m, l.b_v_N_s_per_m + l.b_o_N_s_per_m);
}

// --- pad_2d_damping --------------------------------------------------------------------------

TEST(PadDamping, InclusionHasTwiceTheRetardationTimeAtItsFiveGridPointsAndTheSameElasticLaw) {
  const PadPhantom& plain = pad("pad_2d");
  const PadPhantom& damped = pad("pad_2d_damping");
  int inside = 0;
  for (const ProbeSite& s : damped.sites()) {
    const ContactParams a = plain.contact_params(s.x_m, s.y_m);
    const ContactParams b = damped.contact_params(s.x_m, s.y_m);
    EXPECT_EQ(a.e_star_Pa, b.e_star_Pa);
    EXPECT_EQ(a.layer_thickness_m, b.layer_thickness_m);
    EXPECT_EQ(a.structural_compliance_m_per_N, b.structural_compliance_m_per_N);
    EXPECT_EQ(a.sls_relaxation_time_s, b.sls_relaxation_time_s);
    EXPECT_EQ(a.sls_strength, b.sls_strength);
    EXPECT_EQ(a.channel_gain_m3_per_N, b.channel_gain_m3_per_N);
    const bool in = (s.row == 5 && s.column >= 3 && s.column <= 5) ||
                    (s.column == 4 && s.row >= 4 && s.row <= 6);
    EXPECT_EQ(b.retardation_time_s, in ? 4e-3 : 2e-3) << s.row << ", " << s.column;
    inside += in;
  }
  EXPECT_EQ(inside, 5);
}

TEST(PadDamping, InclusionRaisesZetaMoreThan1Point7FoldAtTheSameOmegaN) {
  const Linearisation a = linearised_at("pad_2d", 5, 4, 1.0);
  const Linearisation b = linearised_at("pad_2d_damping", 5, 4, 1.0);
  std::printf("(5, 4) at 1.0 A: omega_n %.2f / %.2f rad/s, zeta %.4f / %.4f (pad / damping)\n",
              a.omega_n_rad_per_s, b.omega_n_rad_per_s, a.zeta, b.zeta);
  EXPECT_EQ(a.omega_n_rad_per_s, b.omega_n_rad_per_s);
  // b_o doubles: (b_v + 2 tau k_o + b_sls) / (b_v + tau k_o + b_sls)
  const double want = (a.b_N_s_per_m + a.b_o_N_s_per_m) / a.b_N_s_per_m;
  EXPECT_NEAR(b.zeta / a.zeta, want, 1e-12);
  EXPECT_GT(want, 1.7);
}

TEST(PadDamping, SimulatedStaircaseGivesThePadsQuasiStaticStiffnessInsideTheInclusion) {
  auto k_fd = [](const char* name) {
    test::Rig rig{PlantConfig{}, load_shipped_phantom(name)};
    const ProbeSite s = rig.plant.phantom()->grid_point(5, 4);
    test::touch_at_float(rig, s.x_m, s.y_m);
    rig.run(0.5, 0.2);
    const auto pts = test::staircase(rig, 0.5, 0.01, 0.025, 1.5, 1.5e-3, 0.025);
    std::vector<double> d, f;
    for (const auto& p : pts) {
      if (p.depth_m < 0.25e-3 || p.depth_m > 0.75e-3) continue;
      d.push_back(p.depth_m);
      f.push_back(p.force_N);
    }
    return test::fit_line(d, f).slope;
  };
  const double plain = k_fd("pad_2d"), damped = k_fd("pad_2d_damping");
  std::printf("(5, 4): k_fd %.4f N/mm (pad), %.4f N/mm (damping)\n", plain * 1e-3, damped * 1e-3);
  EXPECT_NEAR(damped, plain, 0.01 * plain);
}

TEST(PadDamping, IncompleteOrOversizedInclusionIsRefusedAtItsLine) {
  std::string text(shipped_phantom_text("pad_2d_damping"));
  const std::string key = "damping_inclusion_radius_m = 0.012";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  std::string missing = text;
  missing.erase(at, key.size());
  EXPECT_THROW(
      {
        try {
          (void)parse_phantom(missing, "x.phantom");
        } catch (const PhantomError& e) {
          EXPECT_NE(std::string(e.what()).find("damping_inclusion_radius_m"), std::string::npos)
              << e.what();
          throw;
        }
      },
      PhantomError);
  std::string big = text;
  big.replace(at, key.size(), "damping_inclusion_radius_m = 0.05");
  try {
    (void)parse_phantom(big, "x.phantom");
    FAIL() << "no throw";
  } catch (const PhantomError& e) {
    EXPECT_NE(std::string(e.what()).find("the damping inclusion runs past the pad"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace palp::plant
