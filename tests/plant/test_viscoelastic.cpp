// SPDX-License-Identifier: Apache-2.0
// Viscoelasticity: the Kelvin-Voigt force grows with indentation rate (so the ramp rate shows in
// the force-depth loop), and the standard-linear-solid option relaxes, creeps and stiffens with
// frequency while keeping the relaxed law the phantoms were tuned with.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "palp/plant/plant.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

using test::kR;

ContactParams solid_position3() {
  const auto ph = load_shipped_phantom("solid_1d");
  const ProbeSite s = ph->position(3);
  return ph->contact_params(s.x_m, s.y_m);
}

TEST(KelvinVoigt, ForceGrowsLinearlyWithIndentationRate) {
  const ContactParams p = solid_position3();
  const ElasticPoint el = elastic_contact(p, kR, 2e-3);
  for (double rate : {0.0, 1e-3, 1e-2, -5e-3}) {
    ContactModel m;
    const auto out = m.evaluate(p, kR, 2e-3, rate, 50e-6);
    EXPECT_NEAR(out.force_N, el.force_N + p.retardation_time_s * el.stiffness_N_per_m * rate,
                1e-12);
  }
  ContactModel m;  // never pulls: a fast retraction leaves the surface behind
  EXPECT_EQ(m.evaluate(p, kR, 2e-3, -10.0, 50e-6).force_N, 0.0);
}

// A triangle current ramp 0.5 -> 1.5 -> 0.5 A at two rates on the solid object, position 3.
struct Loop {
  double viscous_at_2mm_N = 0.0, predicted_at_2mm_N = 0.0;
  double area_N_m = 0.0;  // area of the F_o-depth loop (paper's F_o from current and encoder)
};

Loop triangle(double half_period_s) {
  test::Rig rig{PlantConfig{}, load_shipped_phantom("solid_1d")};
  const ProbeSite s = rig.plant.phantom()->position(3);
  test::touch_at_float(rig, s.x_m, s.y_m);
  const double dt = rig.plant.config().tick_period_s;
  const auto n = std::llround(half_period_s / dt);
  Loop out;
  double prev_depth = 0.0, prev_force = 0.0;
  bool measured = false;
  for (long long k = 0; k <= 2 * n; ++k) {
    const double phase = static_cast<double>(k < n ? k : 2 * n - k) / static_cast<double>(n);
    const double i = 0.5 + 1.0 * phase;
    rig.tick(i);
    if (!measured && k < n && rig.plant.indentation_m() >= 2e-3) {
      const ContactParams law = rig.plant.contact_params();
      const ElasticPoint el = elastic_contact(law, kR, rig.plant.indentation_m());
      out.viscous_at_2mm_N = rig.plant.contact_force_N() - el.force_N;
      out.predicted_at_2mm_N =
          law.retardation_time_s * el.stiffness_N_per_m * rig.plant.velocity_m_per_s();
      measured = true;
    }
    const double depth = (rig.plant.encoder_count() - 25000) * 1e-6;
    const double force = test::kKf * (i - test::kIc) - test::kKv * depth;
    if (k > 0) out.area_N_m += 0.5 * (force + prev_force) * (depth - prev_depth);
    prev_depth = depth;
    prev_force = force;
  }
  return out;
}

TEST(KelvinVoigt, RampRateShowsInTheForceDepthLoop) {
  const Loop slow = triangle(5.0), fast = triangle(0.25);
  std::printf(
      "viscous force at 2 mm: slow %.4f N (model %.4f), fast %.4f N (model %.4f); "
      "loop area slow %.3g, fast %.3g N m\n",
      slow.viscous_at_2mm_N, slow.predicted_at_2mm_N, fast.viscous_at_2mm_N,
      fast.predicted_at_2mm_N, slow.area_N_m, fast.area_N_m);
  EXPECT_NEAR(fast.viscous_at_2mm_N, fast.predicted_at_2mm_N, 1e-9);
  EXPECT_GT(fast.viscous_at_2mm_N, 10.0 * slow.viscous_at_2mm_N);
  EXPECT_GT(fast.viscous_at_2mm_N, 0.005);        // > 5 mN at 4 A/s
  EXPECT_GT(fast.area_N_m, 5.0 * slow.area_N_m);  // loading above unloading, more so when fast
}

ContactParams with_sls(double tau1, double g1) {
  ContactParams p = solid_position3();
  p.viscoelasticity = Viscoelasticity::standard_linear_solid;
  p.sls_relaxation_time_s = tau1;
  p.sls_strength = g1;
  return p;
}

TEST(StandardLinearSolid, RelaxesFromInstantaneousToRelaxedForceUnderHeldDepth) {
  const ContactParams p = with_sls(1.0, 0.5);
  const double relaxed = elastic_contact(p, kR, 2e-3).force_N;
  ContactModel m;
  m.evaluate(p, kR, 0.0, 0.0, 1e-3);
  const double dt = 1e-3;
  double f0 = m.evaluate(p, kR, 2e-3, 0.0, dt).force_N;  // step to 2 mm within one step
  double f_tau = 0.0, f_end = 0.0;
  for (int k = 1; k <= 10000; ++k) {
    const double f = m.evaluate(p, kR, 2e-3, 0.0, dt).force_N;
    if (k == 1000) f_tau = f;
    f_end = f;
  }
  EXPECT_NEAR(f0, relaxed * 1.5, 0.001 * relaxed);
  EXPECT_NEAR(f_tau, relaxed * (1.0 + 0.5 * std::exp(-1.0) * std::exp(-1e-3)), 0.002 * relaxed);
  EXPECT_NEAR(f_end, relaxed, 1e-4 * relaxed);
}

TEST(StandardLinearSolid, StiffensWithFrequency) {
  const ContactParams p = with_sls(0.5, 0.4);
  auto in_phase_stiffness = [&](double f_hz) {
    const double w = 2 * std::numbers::pi * f_hz, x0 = 2e-3, a = 1e-5;
    const int per_period = 400, periods = 10;
    const double dt = 1.0 / f_hz / per_period;
    ContactModel m;
    for (int k = 0; k < 100; ++k) m.evaluate(p, kR, x0, 0.0, p.sls_relaxation_time_s);  // relax
    double re = 0.0;
    for (int k = 0; k < per_period * periods; ++k) {
      const double t = (k + 1) * dt;
      re += m.evaluate(p, kR, x0 + a * std::sin(w * t), 0.0, dt).force_N * std::sin(w * t);
    }
    return re / (0.5 * per_period * periods * a);
  };
  const double k_static = elastic_contact(p, kR, 2e-3).stiffness_N_per_m;
  EXPECT_NEAR(in_phase_stiffness(0.002), k_static, 0.02 * k_static);
  EXPECT_NEAR(in_phase_stiffness(50.0), 1.4 * k_static, 0.02 * k_static);
}

// The option through a phantom file: a current step creeps in, ending at the relaxed depth.
TEST(StandardLinearSolid, PhantomOptionMakesTheProbeCreepUnderConstantCurrent) {
  std::string s(shipped_phantom_text("solid_1d"));
  const std::string kv = "viscoelasticity = kelvin_voigt";
  s.replace(s.find(kv), kv.size(), "viscoelasticity = standard_linear_solid");
  s += "sls_relaxation_time_s = 1.0\nsls_strength = 0.5\n";
  const auto sls = parse_phantom(s, "solid_sls");
  auto depth_after = [](std::shared_ptr<const Phantom> ph, double seconds) {
    test::Rig rig{PlantConfig{}, ph};
    const ProbeSite site = ph->position(3);
    test::touch_at_float(rig, site.x_m, site.y_m);
    double sum = 0.0;
    rig.run(1.0, seconds - 0.1);
    rig.run(1.0, 0.1, [&](const Plant& p) { sum += p.indentation_m() / 2000.0; });
    return sum;
  };
  const double early = depth_after(sls, 0.3), late = depth_after(sls, 8.0);
  const double kelvin_voigt = depth_after(load_shipped_phantom("solid_1d"), 2.0);
  std::printf("creep at 1.0 A: %.3f mm at 0.3 s, %.3f mm at 8 s (Kelvin-Voigt %.3f mm)\n",
              early * 1e3, late * 1e3, kelvin_voigt * 1e3);
  EXPECT_LT(early, late - 0.2e-3);
  EXPECT_NEAR(late, kelvin_voigt, 0.01 * kelvin_voigt);
}

}  // namespace
}  // namespace palp::plant
