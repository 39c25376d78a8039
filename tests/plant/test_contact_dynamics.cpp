// SPDX-License-Identifier: Apache-2.0
// Contact dynamics at position 3 under the paper's 1.0 A bias (§IV-B): a small ring-down about
// the operating point shows the paper's natural frequencies and damping ratios (insert > solid >
// hollow), which the participating masses and Kelvin-Voigt retardation times were chosen for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "palp/plant/plant.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

struct Dyn {
  const char* name;
  double omega_n, zeta;  // paper §IV-B
};

test::RingDown ring_down_at_bias(const std::string& name, double* omega_n_model = nullptr) {
  test::Rig rig{PlantConfig{}, load_shipped_phantom(name)};
  const ProbeSite s = rig.plant.phantom()->position(3);
  test::touch_at_float(rig, s.x_m, s.y_m);
  for (int k = 1; k <= 50; ++k) rig.run(0.5 + 0.01 * k, 0.02);  // 1 s ramp to the bias
  rig.run(1.0, 2.0);
  double x_eq = 0.0;
  rig.run(1.0, 0.5, [&](const Plant& p) { x_eq += p.position_m() / 10000.0; });
  if (omega_n_model) {
    const ContactParams law = rig.plant.contact_params();
    const double d = x_eq - rig.plant.config().mechanics.float_position_m;
    const double k = 43.9 + elastic_contact(law, 2.5e-3, d).stiffness_N_per_m;
    *omega_n_model = std::sqrt(k / (0.161 + law.participating_mass_kg));
  }
  rig.plant.reset_state({x_eq + 200e-6, 0.0, rig.plant.coil_current_A()});
  std::vector<double> t, x;
  rig.run(1.0, 1.0, [&](const Plant& p) {
    t.push_back(p.time_s());
    x.push_back(p.position_m());
  });
  return test::analyse_ring_down(t, x, x_eq, 4);
}

TEST(ContactDynamics, RingDownAtPosition3MatchesPapersOmegaNAndZeta) {
  const Dyn cases[] = {
      {"insert_1d", 78.673, 0.1375}, {"solid_1d", 66.3066, 0.1258}, {"hollow_1d", 42.3921, 0.1330}};
  double previous = 1e9;
  for (const Dyn& c : cases) {
    double wn_model = 0.0;
    const auto r = ring_down_at_bias(c.name, &wn_model);
    const double wn = r.omega_d_rad_per_s / std::sqrt(1.0 - r.zeta * r.zeta);
    std::printf(
        "%-9s omega_n = %.2f rad/s (paper %.2f, linearised model %.2f), zeta = %.4f "
        "(paper %.4f)\n",
        c.name, wn, c.omega_n, wn_model, r.zeta, c.zeta);
    EXPECT_NEAR(wn, c.omega_n, 0.03 * c.omega_n) << c.name;  // tolerance 3 %
    EXPECT_NEAR(r.zeta, c.zeta, 0.10 * c.zeta) << c.name;    // tolerance 10 %
    EXPECT_LT(wn, previous);                                 // insert > solid > hollow
    previous = wn;
  }
}

}  // namespace
}  // namespace palp::plant
