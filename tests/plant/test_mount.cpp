// SPDX-License-Identifier: Apache-2.0
// The mount (robot side): an approach at 1 mm/s is seen as 200 counts of coil motion soon after
// touching (paper §II-B); a teleport adds no viscous force, a continuous move does; moving across
// the pad changes the contact law under the tip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "palp/plant/plant.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

TEST(Mount, ApproachAt1mmPerSecondIsDetectedAfter200CountsOfCoilMotion) {
  test::Rig rig{PlantConfig{}, load_shipped_phantom("solid_1d")};
  const ProbeSite s = rig.plant.phantom()->position(3);
  const double sf = rig.plant.config().mechanics.float_position_m;
  const double touch_z = -sf;  // mount z at which the floating tip touches the flat top z = 0
  double z = touch_z - 2e-3;
  rig.plant.set_mount(s.x_m, s.y_m, z);
  rig.start_at(sf, test::kIc);
  rig.run(test::kIc, 0.5);
  const std::int32_t baseline = rig.plant.encoder_count();
  const double dt = rig.plant.config().tick_period_s;
  while (std::abs(rig.plant.encoder_count() - baseline) < 200 && z < touch_z + 2e-3) {
    z += 1e-3 * dt;  // 1 mm/s
    rig.plant.move_mount(s.x_m, s.y_m, z);
    rig.tick(test::kIc);
  }
  const double past = z - touch_z;
  std::printf("contact detected %.3f mm past the touch point, force %.4f N\n", past * 1e3,
              rig.plant.contact_force_N());
  EXPECT_LT(rig.plant.encoder_count(), baseline);  // the coil was pushed back (toward -z)
  EXPECT_GT(past, 0.2e-3);
  EXPECT_LT(past, 0.4e-3);
  EXPECT_NEAR(rig.plant.contact_force_N(), 43.9 * 0.2e-3, 0.004);  // the springs' 0.2 mm
}

TEST(Mount, TeleportAddsNoViscousForceButAContinuousMoveDoes) {
  const auto ph = load_shipped_phantom("solid_1d");
  const ProbeSite s = ph->position(3);
  PlantConfig cfg;
  const double sf = cfg.mechanics.float_position_m;
  Plant teleported(cfg, ph), moved(cfg, ph);
  for (Plant* p : {&teleported, &moved}) {
    p->set_mount(s.x_m, s.y_m, -sf);
    p->reset_state({sf, 0.0, 0.5});
    p->step(2.9);
  }
  const ContactParams law = ph->contact_params(s.x_m, s.y_m);
  auto kelvin_voigt = [&](const Plant& p, double extra_rate) {
    const ElasticPoint el = elastic_contact(law, 2.5e-3, p.indentation_m());
    return el.force_N +
           law.retardation_time_s * el.stiffness_N_per_m * (p.velocity_m_per_s() + extra_rate);
  };
  // A teleport 1 mm deeper: the force is at once the elastic one (plus the coil's own speed).
  teleported.set_mount(s.x_m, s.y_m, -sf + 1e-3);
  EXPECT_NEAR(teleported.indentation_m(), 1e-3 + (teleported.position_m() - sf), 1e-15);
  EXPECT_NEAR(teleported.contact_force_N(), kelvin_voigt(teleported, 0.0), 1e-12);
  // The same 1 mm as a move during one tick: 20 m/s of indentation rate in the viscous term.
  moved.move_mount(s.x_m, s.y_m, -sf + 1e-3);
  moved.step(2.9);
  const double rate = 1e-3 / cfg.tick_period_s;
  EXPECT_NEAR(moved.contact_force_N(), kelvin_voigt(moved, rate), 1e-9);
  EXPECT_GT(moved.contact_force_N(), 10.0 * kelvin_voigt(moved, 0.0));
}

TEST(Mount, MovingAcrossThePadChangesTheContactLawUnderTheTip) {
  const auto ph = load_shipped_phantom("pad_2d");
  Plant p(PlantConfig{}, ph);
  const ProbeSite c7 = ph->grid_point(3, 7), c8 = ph->grid_point(3, 8);
  p.set_mount(c7.x_m, c7.y_m, 0.0);
  const double compliance7 = p.contact_params().structural_compliance_m_per_N;
  p.move_mount(c8.x_m, c8.y_m, 0.0);
  EXPECT_GT(p.contact_params().structural_compliance_m_per_N, 1.5 * compliance7);
  p.move_mount(0.2, 0.2, 0.0);  // off the pad: nothing under the tip
  p.reset_state({0.03, 0.0, 0.0});
  p.step(0.0);
  EXPECT_EQ(p.contact_force_N(), 0.0);
  EXPECT_EQ(p.indentation_m(), 0.0);
}

// 20 kHz and 40 kHz ticks give the same trajectory (ideal current drive, no noise): solid
// object, position 3, a current step from I_c to 1.0 A.
TEST(Integrator, TrajectoryIsTheSameAt20And40kHz) {
  auto run = [](double dt) {
    PlantConfig cfg;
    cfg.tick_period_s = dt;
    const auto ph = load_shipped_phantom("solid_1d");
    Plant p(cfg, ph);
    const ProbeSite s = ph->position(3);
    p.set_mount(s.x_m, s.y_m, -cfg.mechanics.float_position_m);
    p.reset_state({cfg.mechanics.float_position_m, 0.0, 1.0});
    std::vector<double> x;
    const auto per_ms = std::lround(1e-3 / dt);
    for (int ms = 0; ms < 500; ++ms) {
      for (long k = 0; k < per_ms; ++k) {
        p.step(1.0 * cfg.coil.resistance_ohm + p.force_constant_N_per_A() * p.velocity_m_per_s());
      }
      x.push_back(p.position_m());
    }
    return x;
  };
  const auto a = run(50e-6), b = run(25e-6);
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k]));
  std::printf("20 vs 40 kHz: largest position difference %.3f um over 0.5 s\n", worst * 1e6);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace palp::plant
