// SPDX-License-Identifier: Apache-2.0
// The plant's small-signal linearisation (linearisation.hpp): the static equilibrium it solves
// is where the simulated coil settles, and its omega_n / zeta are the numbers the phantoms were
// tuned to (solid position 3 at 1.0 A: 66.31 rad/s, phantom file) and the free-air 16.51 rad/s.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "palp/plant/linearisation.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

TEST(Linearisation, FreeAirAtTheFloatCurrentIsTheSpringMassDamper) {
  const Linearisation l = linearise_free_air(PlantConfig{}, 0.5);
  EXPECT_FALSE(l.in_contact);
  EXPECT_NEAR(l.stroke_m, 0.025, 1e-12);  // the float position, by the preload's definition
  EXPECT_DOUBLE_EQ(l.k_N_per_m, 43.9);    // K_f flat there: no hidden spring
  EXPECT_DOUBLE_EQ(l.m_kg, 0.161);
  EXPECT_DOUBLE_EQ(l.b_N_s_per_m, 1.38);
  EXPECT_NEAR(l.omega_n_rad_per_s, 16.51, 0.005);
  EXPECT_NEAR(l.zeta, 0.2596, 0.0001);
  EXPECT_NEAR(l.kf_N_per_A, 2.918, 1e-12);
}

TEST(Linearisation, FreeAirStrokeMovesKfOverKvPerAmpere) {
  const Linearisation l = linearise_free_air(PlantConfig{}, 0.6);
  EXPECT_NEAR(l.stroke_m, 0.025 + 0.1 * 2.918 / 43.9, 1e-9);  // 6.65 mm further
}

TEST(Linearisation, BehindTheFlatPartOfTheTableTheCoilAddsItsHiddenSpring) {
  // At 0.4 A the coil floats behind 23.5 mm, where K_f falls by 0.142 N/A per mm: k gains
  // -i dK_f/ds = 0.4 x 141.9 N/m.
  const Linearisation l = linearise_free_air(PlantConfig{}, 0.4);
  ASSERT_LT(l.stroke_m, 0.0235);
  const double slope = (2.918 - 3.84) / (0.0235 - 0.017);
  EXPECT_NEAR(l.k_coil_N_per_m, -0.4 * slope, 1e-9);
  EXPECT_NEAR(l.k_N_per_m, 43.9 - 0.4 * slope, 1e-9);
}

TEST(Linearisation, EquilibriumOnAnEndStopIsRefusedNamingTheStop) {
  try {
    (void)linearise_free_air(PlantConfig{}, 0.0);
    FAIL() << "no throw";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("rear end stop"), std::string::npos) << e.what();
  }
  try {
    (void)linearise_free_air(PlantConfig{}, 2.0);
    FAIL() << "no throw";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("front end stop"), std::string::npos) << e.what();
  }
}

TEST(Linearisation, SolidPosition3AtOneAmpereGivesTheTunedOmegaN) {
  test::Rig rig{PlantConfig{}, load_shipped_phantom("solid_1d")};
  const ProbeSite p3 = rig.plant.phantom()->position(3);
  test::touch_at_float(rig, p3.x_m, p3.y_m);
  const Linearisation l = linearise(rig.plant, 1.0);
  ASSERT_TRUE(l.in_contact);
  EXPECT_NEAR(l.depth_m, 2.75e-3, 0.01e-3);           // README: operating depth 2.75 mm
  EXPECT_NEAR(l.k_o_N_per_m, 726.0, 1.0);             // the law's tangent 0.726 N/mm
  EXPECT_NEAR(l.m_kg, 0.161 + 0.01416, 1e-12);        // mass fully engaged beyond 1 mm
  EXPECT_NEAR(l.b_o_N_s_per_m, 2.124e-3 * l.k_o_N_per_m, 1e-12);
  EXPECT_NEAR(l.omega_n_rad_per_s, 66.31, 0.05);      // phantom file: tuned to 66.31 rad/s
  // Force balance: K_f (i - I_c) = k_v delta + F_o with the coil floating at contact.
  EXPECT_NEAR(l.contact_force_N + 43.9 * l.depth_m, 2.918 * 0.5, 1e-9);
}

TEST(Linearisation, EquilibriumIsWhereTheSimulatedCoilSettles) {
  for (const char* name : {"hollow_1d", "solid_1d", "insert_1d"}) {
    test::Rig rig{PlantConfig{}, load_shipped_phantom(name)};
    const ProbeSite p3 = rig.plant.phantom()->position(3);
    test::touch_at_float(rig, p3.x_m, p3.y_m);
    for (int k = 1; k <= 50; ++k) rig.run(0.5 + 0.01 * k, 0.02);
    rig.run(1.0, 2.0);
    double s_mean = 0.0;
    rig.run(1.0, 0.5, [&](const Plant& p) { s_mean += p.position_m() / 10000.0; });
    const Linearisation l = linearise(rig.plant, 1.0);
    EXPECT_NEAR(l.stroke_m, s_mean, 0.2e-6) << name;  // noise: 2 mA x K_f / k ~ 10 nm
  }
}

TEST(Linearisation, OrderingAndDampingOfThe1DObjectsAtPosition3) {
  double wn[3], zeta[3];
  const char* names[3] = {"insert_1d", "solid_1d", "hollow_1d"};
  for (int k = 0; k < 3; ++k) {
    test::Rig rig{PlantConfig{}, load_shipped_phantom(names[k])};
    const ProbeSite p3 = rig.plant.phantom()->position(3);
    test::touch_at_float(rig, p3.x_m, p3.y_m);
    const Linearisation l = linearise(rig.plant, 1.0);
    wn[k] = l.omega_n_rad_per_s;
    zeta[k] = l.zeta;
  }
  // README "Phantoms": tuned to the paper's 78.67 / 66.31 / 42.39 rad/s, zeta 0.1375 / 0.1258 /
  // 0.1330.
  EXPECT_GT(wn[0], wn[1]);
  EXPECT_GT(wn[1], wn[2]);
  EXPECT_NEAR(wn[0], 78.67, 0.1);
  EXPECT_NEAR(wn[2], 42.39, 0.1);
  EXPECT_NEAR(zeta[0], 0.1375, 0.002);
  EXPECT_NEAR(zeta[1], 0.1258, 0.002);
  EXPECT_NEAR(zeta[2], 0.1330, 0.002);
}

}  // namespace
}  // namespace palp::plant
