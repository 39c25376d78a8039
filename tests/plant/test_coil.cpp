// SPDX-License-Identifier: Apache-2.0
// Coil: the K_f(s) table (points, flat working range), RL electrics, supply clamp, back-EMF.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "palp/plant/plant.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

TEST(ForceConstant, TableCarriesThePapersPoints) {
  const ForceConstantTable kf(default_kf_table());
  EXPECT_DOUBLE_EQ(kf.at(0.017), 3.84);                      // mid-stroke (§II-A)
  EXPECT_DOUBLE_EQ(kf.at(0.024), 2.918);                     // 24 mm travel (§II-A)
  EXPECT_DOUBLE_EQ(kf.at(0.0235), 2.918);                    // where the flat part starts
  EXPECT_NEAR(kf.at(0.02025), 0.5 * (3.84 + 2.918), 1e-12);  // linear between points
}

TEST(ForceConstant, FlatWithin0p0005NPerAPerMmFrom1mmBehindTo6mmBeyondFloat) {
  const PlantConfig cfg;
  const ForceConstantTable kf(cfg.coil.kf_table);
  const double sf = cfg.mechanics.float_position_m;
  for (double s = sf - 1e-3; s <= sf + 6e-3 + 1e-12; s += 1e-5) {
    EXPECT_LT(std::abs(kf.slope(s)) * 1e-3, 0.0005) << "s = " << s;
    EXPECT_NEAR(kf.at(s), 2.918, 1e-12) << "s = " << s;
  }
}

TEST(ForceConstant, RisesTowardMidStrokeOnlyBehindTheWorkingRange) {
  const ForceConstantTable kf(default_kf_table());
  EXPECT_GT(kf.at(0.020), 2.918);
  EXPECT_LT(kf.at(0.020), 3.84);
  EXPECT_LT(kf.slope(0.020), 0.0);
  EXPECT_DOUBLE_EQ(kf.at(0.034), 2.918);
}

TEST(ForceConstant, RejectsUnorderedOrNonPositivePoints) {
  EXPECT_THROW(ForceConstantTable({{0.0, 3.0}}), std::invalid_argument);
  EXPECT_THROW(ForceConstantTable({{0.01, 3.0}, {0.0, 3.0}}), std::invalid_argument);
  EXPECT_THROW(ForceConstantTable({{0.0, 3.0}, {0.01, 0.0}}), std::invalid_argument);
}

// A blocked coil (pressed onto the rear stop by its own negative current) is a pure RL circuit.
TEST(CoilElectrics, BlockedCoilCurrentRisesWithTimeConstantLOverR) {
  PlantConfig cfg;
  cfg.sensors.current_sense_noise_A = 0.0;
  Plant p(cfg);
  const double tau = cfg.coil.inductance_H / cfg.coil.resistance_ohm;  // 0.357 ms
  const double v = -5.8;                                               // -> -1 A
  const double dt = 12.5e-6;
  const int n = static_cast<int>(std::lround(tau / dt));
  for (int k = 0; k < n; ++k) p.step(dt, v);
  EXPECT_TRUE(p.at_rear_stop());
  EXPECT_NEAR(p.coil_current_A(), -(1.0 - std::exp(-n * dt / tau)), 1e-9);
  for (int k = 0; k < 400; ++k) p.step(v);
  EXPECT_NEAR(p.coil_current_A(), -1.0, 1e-6);
}

TEST(CoilElectrics, ExactUpdateIsIndependentOfTickRate) {
  PlantConfig cfg;
  Plant a(cfg), b(cfg);
  for (int k = 0; k < 20; ++k) a.step(50e-6, -3.0);
  for (int k = 0; k < 40; ++k) b.step(25e-6, -3.0);
  EXPECT_NEAR(a.coil_current_A(), b.coil_current_A(), 1e-12);
}

TEST(CoilElectrics, VoltageIsClampedToThe24VSupply) {
  PlantConfig cfg;
  Plant clamped(cfg), at_supply(cfg);
  clamped.step(100.0);
  at_supply.step(24.0);
  EXPECT_DOUBLE_EQ(clamped.coil_current_A(), at_supply.coil_current_A());
  EXPECT_GT(at_supply.coil_current_A(), 0.5);  // 24 V / 5.8 Ohm x (1 - e^-0.14)
}

TEST(CoilElectrics, BackEmfOpposesMotionWithKfTimesVelocity) {
  PlantConfig cfg;
  Plant p(cfg);
  p.reset_state({0.027, 0.1, 0.0});  // moving toward +z at 0.1 m/s, 0 V across the coil
  std::vector<double> speed;
  for (int k = 0; k < 60; ++k) {  // 3 ms: 8 electrical time constants
    p.step(0.0);
    speed.push_back(p.velocity_m_per_s());
  }
  // The current follows -K_f v / R one electrical time constant late (the coil decelerates).
  const double tau = cfg.coil.inductance_H / cfg.coil.resistance_ohm;
  const auto lag = static_cast<std::size_t>(std::lround(tau / cfg.tick_period_s));
  const double expected =
      -p.force_constant_N_per_A() * speed[speed.size() - 1 - lag] / cfg.coil.resistance_ohm;
  EXPECT_LT(p.coil_current_A(), 0.0);
  EXPECT_NEAR(p.coil_current_A(), expected, 0.02 * std::abs(expected));
}

}  // namespace
}  // namespace palp::plant
