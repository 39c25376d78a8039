// SPDX-License-Identifier: Apache-2.0
// What the surface-tracing tests against palp-sim linked in share: the rig that matches
// palp-sim's default frames and the 2D pad's probing grid.
#pragma once

#include <numbers>

#include "palp/rig.hpp"
#include "palp/sim_inproc.hpp"

namespace palp::trace_test {

inline constexpr double kDeg = std::numbers::pi / 180.0;

// palp-sim's defaults: the phantom frame at (600, 0, 300) mm in the base frame, rotated by
// C = 180 deg (phantom +z = base -z); the probe's tip at stroke origin 200 mm along the flange z.
inline palp::Rig sim_rig(const palp::sim::InprocSimulator& sim) {
  palp::Rig rig;
  rig.robot_uri = sim.robot_uri();
  rig.probe_uri = sim.uri();
  rig.tool_id = 1;
  rig.tool_tcp = palp::Pose{0, 0, 0.200, 0, 0, 0};
  rig.safe_height_m = 12e-3;  // above the tilted plane's highest point (8.8 mm)
  rig.approach_speed_m_per_s = 1e-3;
  rig.travel_speed_m_per_s = 0.05;
  rig.work_object = palp::WorkObject{"phantom", palp::Pose{0.600, 0.0, 0.300, 0, 0, 180 * kDeg}};
  return rig;
}

// the 2D pad's probing grid: column c at x = 10 + 10 (c - 1) mm, row r at y = 5 + 10 (r - 1) mm
inline palp::Plan pad_plan(int n) {
  palp::Plan plan;
  plan.name = "pad";
  plan.work_object = "phantom";
  plan.grid.rows = n;
  plan.grid.columns = n;
  plan.grid.x0_m = 0.010;
  plan.grid.y0_m = 0.005;
  plan.grid.pitch_x_m = 0.080 / (n - 1);
  plan.grid.pitch_y_m = 0.080 / (n - 1);
  plan.contact_E_star_Pa = 3.3e6;  // the pad material's E* (hil/plant/phantoms)
  return plan;
}

}  // namespace palp::trace_test
