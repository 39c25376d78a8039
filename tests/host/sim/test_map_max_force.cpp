// SPDX-License-Identifier: Apache-2.0
// MapOptions::max_force_N (palpctl map --max-force-N, force_limit.hpp) on the pad in palp-sim
// linked in, virtual time: each ramp stops at the object force asked, and a force beyond the
// device's current clamp is refused before anything moves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "palp/error.hpp"
#include "palp/force_limit.hpp"
#include "palp/map.hpp"
#include "palp/probe.hpp"
#include "palp/result.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "trace_sim.hpp"

namespace max_force_test {

using palp::sim::InprocSimulator;

using palp::trace_test::sim_rig;

// row 4 of the pad, columns 3, 6 and 9: off the shallow channels, so alike in stiffness
palp::Plan row4_plan() {
  palp::Plan plan = palp::trace_test::pad_plan(3);
  plan.grid.rows = 1;
  plan.grid.x0_m = 0.030;
  plan.grid.y0_m = 0.035;
  plan.grid.pitch_x_m = plan.grid.pitch_y_m = 0.030;
  return plan;
}

std::filesystem::path fresh_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d;
}

// the recorded object force on the first repetition's top step, F_o = K_f (i - I_c) - k_v (z -
// z_c) with the fitted contact point, and the depth there
struct Peak {
  double force_N, depth_m, step_A;
};
Peak recorded_peak(const palp::LoadedResult& r) {
  const palp::IndentationRun run = palp::indentation_run_of(r);
  const palp::analysis::Curve c = palp::curve_of(run.recording);
  const auto& a = run.settings.analysis;
  const double zc = run.analysis->contact_z_m.value.value();
  double top = 0, f = 0, z = 0;
  int n = 0;
  const Eigen::Index n_first = (c.rep.array() == c.rep[0]).count();  // contiguous, from 0
  for (Eigen::Index k = 0; k < n_first; ++k) top = std::max(top, c.i_cmd_A[k]);
  for (Eigen::Index k = 0; k < n_first; ++k)
    if (c.i_cmd_A[k] > top - 1e-6) {
      f += a.force_constant_N_per_A * (c.i_A[k] - a.contact_current_A) -
           a.spring_N_per_m * (c.z_m[k] - zc);
      z += c.z_m[k] - zc;
      ++n;
    }
  return {f / n, z / n, run.settings.step_A};
}

TEST(MapMaxForce, EachRampPeaksWithinAStepOfTheForceOnceThePreviousPointGaveTheDepth) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = fresh_dir("palp_map_max_force");
  palp::MapOptions o;
  o.settings.repetitions = 1;
  o.max_force_N = 5.0;
  const palp::StiffnessMap m = palp::map_plan(probe, *robot, sim_rig(sim), row4_plan(), dir, o);
  ASSERT_TRUE(m.complete) << m.stopped_because;
  ASSERT_EQ(m.points.size(), 3u);
  EXPECT_EQ(palp::load_map(dir).max_force_N, 5.0);  // recorded in map.json
  const double kf = o.settings.analysis.force_constant_N_per_A;
  const double kv = o.settings.analysis.spring_N_per_m;
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(m.points[k].indented) << m.points[k].reason;
    const Peak p = recorded_peak(palp::load_result(dir / m.points[k].result_dir));
    const double step_N = kf * p.step_A;
    std::printf("point %zu: peak F_o %.4f N at %.3f mm (step %.4f N)\n", k + 1, p.force_N,
                p.depth_m * 1e3, step_N);
    EXPECT_LE(p.step_A, 0.01);
    if (k == 0) {  // no depth known yet: the top is F / K_f above I_c, F_o stops k_v delta short
      EXPECT_NEAR(p.force_N, 5.0 - kv * p.depth_m, step_N);
      EXPECT_LT(p.force_N, 5.0);
    } else {
      EXPECT_NEAR(p.force_N, 5.0, step_N);
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(MapMaxForce, AForceBeyondTheDevicesCurrentClampIsRefusedBeforeAnythingMoves) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  palp::Params params = probe.params();
  params.current_clamp_A = 2.5f;
  probe.set_params(params);
  const auto dir = fresh_dir("palp_map_max_force_refused");
  palp::MapOptions o;
  o.max_force_N = 6.0;
  try {
    palp::map_plan(probe, *robot, sim_rig(sim), row4_plan(), dir, o);
    ADD_FAILURE() << "6 N was accepted with a 2.5 A clamp";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "max_force_N 6 N needs up to 2.631 A at the ramp's top (I_c 0.5 A + (6 N + k_v "
                 "43.9 N/m x 5 mm displacement limit) / K_f 2.918 N/A), above the coil's current "
                 "clamp 2.5 A: at most 5.61 N");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "map.json"));
  EXPECT_EQ(probe.status().i_cmd_A, 0.0);
}

}  // namespace max_force_test
