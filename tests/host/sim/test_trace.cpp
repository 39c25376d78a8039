// SPDX-License-Identifier: Apache-2.0
// Surface tracing against palp-sim linked in (palp/sim_inproc.hpp: the probe's transport in
// process, the robot-bridge emulator on a loopback Modbus TCP port, one simulation), with the
// model's own surface as the truth (issue 5's acceptance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "palp/analysis/surface.hpp"
#include "palp/plant/phantom.hpp"
#include "palp/probe.hpp"
#include "palp/protocol/robot_bridge/pose.hpp"
#include "palp/robot.hpp"
#include "palp/trace.hpp"
#include "palp/sim_inproc.hpp"
#include "trace_sim.hpp"

namespace {

using palp::sim::InprocSimulator;
using palp::trace_test::kDeg;
using palp::trace_test::pad_plan;
using palp::trace_test::sim_rig;

struct Errors {
  double max_height_um = 0, max_normal_deg = 0;
};

Errors compare_with_model(const palp::TracedSurface& s, const std::string& phantom) {
  const auto model = palp::plant::load_shipped_phantom(phantom);
  Errors e;
  std::vector<palp::analysis::Vec3> truth;
  for (const palp::TracePoint& p : s.points) {
    EXPECT_TRUE(p.ok) << "row " << p.row << " column " << p.column << ": " << p.reason;
    const double zs = model->surface_z_m(p.x_m, p.y_m);
    e.max_height_um = std::max(e.max_height_um, std::abs(p.z_m - zs) * 1e6);
    if (std::getenv("PALP_TRACE_DEBUG"))
      std::printf("r%d c%d contact (%.4f %.4f %.4f) mm apex (%.4f %.4f %.4f) z_s %.4f err %.1f um F %.4f N ind %.1f um tilt %.2f\n",
                  p.row, p.column, p.x_m * 1e3, p.y_m * 1e3, p.z_m * 1e3, p.apex_x_m * 1e3, p.apex_y_m * 1e3,
                  p.apex_z_m * 1e3, zs * 1e3, (p.z_m - zs) * 1e6, p.detection_force_N, p.indentation_m * 1e6,
                  p.tilt_rad / kDeg);
    truth.emplace_back(p.x_m, p.y_m, zs);
  }
  // the same stencil on the model's heights at the traced (x, y)
  const auto g = palp::analysis::grid_normals(truth, s.rows, s.columns, palp::analysis::Vec3::UnitZ());
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const auto& p = s.points[k];
    const double dot = g.normal[k].dot(palp::analysis::Vec3(p.normal[0], p.normal[1], p.normal[2]));
    e.max_normal_deg = std::max(e.max_normal_deg, std::acos(std::min(1.0, dot)) / kDeg);
  }
  return e;
}

TEST(Trace, NineByNineOnA15DegreeWavyPadLandsWithin20umOfTheModelSurface) {
  InprocSimulator sim({.phantom = "pad_2d_steep", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const palp::Rig rig = sim_rig(sim);
  const palp::TracedSurface s = palp::trace_surface(probe, *robot, rig, pad_plan(9));
  ASSERT_TRUE(s.complete) << s.stopped_because;
  ASSERT_EQ(s.points.size(), 81u);
  const Errors e = compare_with_model(s, "pad_2d_steep");
  EXPECT_LT(e.max_height_um, 20.0);
  EXPECT_LT(e.max_normal_deg, 3.0);
  RecordProperty("max_height_error_um", std::to_string(e.max_height_um));
  RecordProperty("max_normal_error_deg", std::to_string(e.max_normal_deg));
  std::printf("15-degree pad: max height error %.2f um, max normal error %.3f deg\n", e.max_height_um,
              e.max_normal_deg);
}

TEST(Trace, OnAPlaneTilted10DegreesNormalsAreWithinHalfADegree) {
  InprocSimulator sim({.phantom = "plane_tilted_10", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const palp::TracedSurface s = palp::trace_surface(probe, *robot, sim_rig(sim), pad_plan(5));
  ASSERT_TRUE(s.complete) << s.stopped_because;
  const Errors e = compare_with_model(s, "plane_tilted_10");
  EXPECT_LT(e.max_height_um, 20.0);
  EXPECT_LT(e.max_normal_deg, 0.5);
  for (const auto& p : s.points) EXPECT_NEAR(p.tilt_rad / kDeg, 10.0, 0.5) << p.row << "," << p.column;
  std::printf("10-degree plane: max height error %.2f um, max normal error %.3f deg\n", e.max_height_um,
              e.max_normal_deg);
}

TEST(Trace, CancelledMidPlanLeavesTheArmAtTheSafeHeightWithZeroCurrentAndResumesWithoutRepeats) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const palp::Rig rig = sim_rig(sim);
  const palp::Plan plan = pad_plan(3);
  std::size_t done = 0;
  palp::TraceOptions o;
  o.progress = [&](const palp::TraceProgress& p) { done = p.done; };
  o.cancelled = [&] { return done >= 4; };  // Ctrl-C after the fourth point
  const palp::TracedSurface part = palp::trace_surface(probe, *robot, rig, plan, o);
  EXPECT_FALSE(part.complete);
  EXPECT_EQ(part.stopped_because, "cancelled");
  EXPECT_EQ(part.resume_index, 4u);
  EXPECT_EQ(part.points.size(), 4u);
  // the coil current is zero and the tip is above the safe height (whatever the coil does)
  const palp::Status st = probe.status();
  EXPECT_EQ(st.i_cmd_A, 0.0);
  EXPECT_EQ(robot->status().state, palp::proto::rb::RobotState::idle);
  // the TCP (tip at stroke origin) at least safe height + the whole stroke above the datum:
  // base z = 300 mm (the datum) + 12 mm + 34 mm
  EXPECT_GE(robot->pose().z_m, 0.300 + rig.safe_height_m + 0.034 - 1e-6);

  palp::TraceOptions again;
  again.resume = part;
  const palp::TracedSurface whole = palp::trace_surface(probe, *robot, rig, plan, again);
  ASSERT_TRUE(whole.complete) << whole.stopped_because;
  ASSERT_EQ(whole.points.size(), 9u);
  for (std::size_t k = 0; k < 9; ++k) {  // each point once, in order; the first four kept as they were
    EXPECT_EQ(whole.points[k].row, static_cast<int>(k) / 3 + 1);
    EXPECT_EQ(whole.points[k].column, static_cast<int>(k) % 3 + 1);
    if (k < 4) {
      EXPECT_EQ(whole.points[k].apex_z_m, part.points[k].apex_z_m);
    }
  }
}

TEST(Trace, APointWithNoSurfaceBelowItLeavesNoWatchRunningAndTheNextPointIsTraced) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  palp::Plan plan = pad_plan(2);
  plan.grid.rows = 1;
  plan.grid.x0_m = -0.040;  // off the 100 x 90 mm pad: nothing to touch within the search
  plan.grid.pitch_x_m = 0.090;
  const palp::TracedSurface s = palp::trace_surface(probe, *robot, sim_rig(sim), plan);
  ASSERT_EQ(s.points.size(), 2u) << s.stopped_because;
  EXPECT_FALSE(s.points[0].ok);
  EXPECT_EQ(s.points[0].reason.rfind("no contact within ", 0), 0u) << s.points[0].reason;
  // the search's contact watch was stopped with it: the next point's LoadContactWatch was refused
  // busy before
  EXPECT_TRUE(s.points[1].ok) << s.points[1].reason;
  EXPECT_EQ(probe.status().i_cmd_A, 0.0);
}

}  // namespace

namespace {

TEST(TouchOff, ThreeTouchesOnThe10DegreePlaneRegisterItsNormalAndAnOriginOnTheSurface) {
  InprocSimulator sim({.phantom = "plane_tilted_10", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  palp::Rig rig = sim_rig(sim);
  rig.work_object.reset();
  // above phantom (20, 20), (80, 20), (20, 70) mm; base = (600 + x, -y, 300 - z); the floating
  // tip is ~32 mm ahead of the TCP and the plane is 5.3 mm high at x = 20, 5.3 mm low at x = 80
  const palp::Pose start[3] = {palp::Pose{0.620, -0.020, 0.342, 0, 0, 180 * kDeg},
                               palp::Pose{0.680, -0.020, 0.332, 0, 0, 180 * kDeg},
                               palp::Pose{0.620, -0.070, 0.342, 0, 0, 180 * kDeg}};
  const palp::Pose frame = palp::touch_off(probe, *robot, rig, start, 3.3e6);
  const palp::Pose phantom{0.600, 0.0, 0.300, 0, 0, 180 * kDeg};
  // the origin, in the phantom frame, lies on the plane
  const auto o = palp::analysis::base_to_frame(phantom, palp::analysis::Vec3(frame.x_m, frame.y_m, frame.z_m));
  const auto model = palp::plant::load_shipped_phantom("plane_tilted_10");
  EXPECT_NEAR(o.z(), model->surface_z_m(o.x(), o.y()), 10e-6);
  EXPECT_NEAR(o.x(), 0.020, 1e-3);  // the sphere touches 0.43 mm off the apex on 10 degrees
  EXPECT_NEAR(o.y(), 0.020, 1e-4);
  // its z axis is the plane's normal into the specimen, (-sin 10, 0, cos 10) in the phantom frame
  namespace rb = palp::proto::rb;
  const rb::Rotation to_phantom = rb::transpose(rb::rotation_from_abc(0, 0, 180 * kDeg));
  const rb::Rotation f = rb::rotation_from_abc(frame.a_rad, frame.b_rad, frame.c_rad);
  const double z_base[3] = {f.m[0][2], f.m[1][2], f.m[2][2]};
  double z[3];
  rb::rotate(to_phantom, z_base, z);
  const double n[3] = {-std::sin(10 * kDeg), 0, std::cos(10 * kDeg)};
  const double dot = z[0] * n[0] + z[1] * n[1] + z[2] * n[2];
  EXPECT_LT(std::acos(std::min(1.0, dot)) / kDeg, 0.5);
  // afterwards the coil current is zero
  EXPECT_EQ(probe.status().i_cmd_A, 0.0);
}

}  // namespace
