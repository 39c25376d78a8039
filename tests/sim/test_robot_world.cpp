// SPDX-License-Identifier: Apache-2.0
// RobotWorld in process: the frames of the shared world (probe on the flange, phantom in the base
// frame), the plant's mount following the arm, and the contact line's latency to input 1.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "palp/sim/robot_world.hpp"

namespace palp::sim {
namespace {

struct World {
  explicit World(RobotWorldOptions o = {}, const char* phantom = "none") {
    fw::DeviceIdentity id;
    id.board = "palp-sim";
    sim = std::make_unique<Simulation>(id, std::make_unique<ModelPlant>("none", 1));
    world = std::make_unique<RobotWorld>(*sim, o);
    auto p =
        std::make_unique<ArmMountedPlant>(std::make_unique<ModelPlant>(phantom, 1), *world, *sim);
    plant = &p->inner().model();
    sim->set_plant(std::move(p));
  }
  void tip(double out[3]) const { world->tip_in_phantom(out); }
  // the probe as the tool (the bare flange stands outside the 0.8 m workspace sphere)
  void probe_tool() {
    plant::Transform probe;
    probe.t[2] = 0.2;
    ASSERT_TRUE(world->arm().set_tool(probe));
  }
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<RobotWorld> world;
  plant::Plant* plant = nullptr;
};

TEST(RobotWorld, StartsWithTheTipFiftyMmAboveThePhantomOriginAndTheFlangeAbove) {
  World w;
  double t[3];
  w.tip(t);
  EXPECT_NEAR(t[0], 0.0, 1e-12);
  EXPECT_NEAR(t[1], 0.0, 1e-12);
  EXPECT_NEAR(t[2], -0.050, 1e-12);
  const plant::Transform f = w.world->arm().flange();  // phantom origin (0.6, 0, 0.3), 50 + 200 mm up
  EXPECT_NEAR(f.t[0], 0.6, 1e-12);
  EXPECT_NEAR(f.t[2], 0.55, 1e-12);
  EXPECT_NEAR(f.r.m[2][2], -1.0, 1e-12);  // the flange's z (the probe's axis) points down
}

TEST(RobotWorld, ThePlantsMountFollowsTheArm) {
  World w;
  w.sim->run(20, 0);
  const double z0 = w.plant->tip_z_m();
  w.probe_tool();
  plant::Transform down;  // 10 mm along the tool's z: into the phantom
  down.t[2] = 0.010;
  ASSERT_TRUE(w.world->arm().move_lin_rel(down, 0.1));
  w.sim->run(20000, 0);  // 1 s: the 10 mm move is over
  EXPECT_FALSE(w.world->arm().moving());
  double t[3];
  w.tip(t);
  EXPECT_NEAR(t[2], -0.040, 1e-12);
  EXPECT_NEAR(w.plant->tip_z_m() - z0, 0.010, 1e-6);  // the coil stays parked: the tip moved 10 mm
}

TEST(RobotWorld, APhantomFrameTurnedByAMapsBaseXOntoPhantomY) {
  RobotWorldOptions o;
  o.phantom_frame_deg[0] = 90;  // A = 90 deg, C = 180 deg
  World w(o);
  w.probe_tool();
  plant::Transform target = w.world->arm().tcp();
  target.t[0] += 0.010;
  ASSERT_TRUE(w.world->arm().move_lin(target, 0.1));
  w.sim->run(20000, 0);
  double t[3];
  w.tip(t);
  EXPECT_NEAR(t[0], 0.0, 1e-12);
  EXPECT_NEAR(t[1], 0.010, 1e-12);
  EXPECT_NEAR(t[2], -0.050, 1e-12);
}

TEST(RobotWorld, TheContactLineReachesDigitalInput1AfterTheInputLatency) {
  World w;  // 1 ms at 50 us per tick: 20 ticks
  int ticks = 0;
  while (w.world->bridge().digital_inputs() == 0 && ticks < 100) {
    w.world->tick(50e-6, *w.plant, true);
    ++ticks;
  }
  EXPECT_EQ(ticks, 21);  // the 21st tick sees the level of the 1st
  for (int k = 0; k < 20; ++k) w.world->tick(50e-6, *w.plant, false);
  EXPECT_EQ(w.world->bridge().digital_inputs(), 1);
  w.world->tick(50e-6, *w.plant, false);
  EXPECT_EQ(w.world->bridge().digital_inputs(), 0);
}

TEST(RobotWorld, AStopWriteIsTheReactionToAHeldContactAndLandsTheLatencyLater) {
  World w;
  w.sim->options().reaction_latency_ms = 2.0;
  w.sim->options().hold_timeout_ms = 60'000.0;
  auto send = [&](const auto& m, proto::u16 seq) {
    std::vector<proto::u8> b(proto::kMaxWireFrame);
    b.resize(proto::encode_message(m, seq, 0, b.data(), b.size()));
    w.sim->host_bytes(b.data(), b.size(), 0);
  };
  send(proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "test"}, 0);
  // free air: 0.7 A pushes the coil forward, 200 um fire the watch, the event holds time
  send(proto::LoadContactWatch{0.7f, 200, 0.0f}, 1);
  send(proto::ProgramStart{}, 2);
  for (int k = 0; k < 2000 && !w.sim->holding(); ++k) {
    w.sim->run(20, 0);
    w.sim->take_device_bytes();
  }
  ASSERT_TRUE(w.sim->holding());
  const std::uint64_t held_at = w.sim->ticks();
  const std::uint16_t beat[1] = {5};
  ASSERT_EQ(w.world->write(200, beat, true), ModbusException::none);
  EXPECT_TRUE(w.sim->holding());  // a heartbeat is no reaction
  const std::uint16_t stop[1] = {1};
  ASSERT_EQ(w.world->write(201, stop, true), ModbusException::none);
  EXPECT_FALSE(w.sim->holding());
  while (w.world->bridge().control().stop_request != 1 && w.sim->ticks() < held_at + 200)
    w.sim->run(1, 0);
  // 2 ms = 40 ticks after the event, taken by the first 1 ms cycle at or after it
  EXPECT_GE(w.sim->ticks() - held_at, 40u);
  EXPECT_LT(w.sim->ticks() - held_at, 61u);
  EXPECT_EQ(w.world->bridge().status().stop_seen, 1);
}

// --- the probe's axis (hil/plant/README.md "Oblique contact") -------------------------------

constexpr double kDeg = std::numbers::pi / 180.0;

// Turn the tool about its own y axis by b_deg (the TCP, the tip apex, stays where it is).
void tilt_tool_about_y(World& w, double b_deg) {
  w.probe_tool();
  const plant::Transform turn = plant::pose_from_xyzabc(0, 0, 0, 0, b_deg * kDeg, 0);
  ASSERT_TRUE(w.world->arm().move_lin_rel(turn, 0.1));
  w.sim->run(40000, 0);  // 2 s: 0.44 rad counts as 44 mm of path
  ASSERT_FALSE(w.world->arm().moving());
}

TEST(RobotWorld, TheProbesAxisAndItsWeightFollowTheFlangesOrientation) {
  World w;
  EXPECT_EQ(w.plant->probe_axis(), (std::array<double, 3>{0.0, 0.0, 1.0}));  // vertical: exact
  EXPECT_EQ(w.plant->config().mechanics.gravity_axis_cosine, 1.0);
  tilt_tool_about_y(w, 25.0);
  // the flange's axes start along the phantom's: its z turned about y is (sin, 0, cos)
  const auto a = w.plant->probe_axis();
  EXPECT_NEAR(a[0], std::sin(25 * kDeg), 1e-9);
  EXPECT_NEAR(a[1], 0.0, 1e-9);
  EXPECT_NEAR(a[2], std::cos(25 * kDeg), 1e-9);
  EXPECT_NEAR(w.plant->config().mechanics.gravity_axis_cosine, std::cos(25 * kDeg), 1e-9);
}

TEST(RobotWorld, AToolAlignedWithTheWedgesNormalPressesAlongItWithTheFlatLaw) {
  RobotWorldOptions o;  // the tip 10 mm above the wedge's x = 50, y = 35 mm (where z_s = 0)
  o.start_at_tip_mm = true;
  o.start_tip_mm[0] = 650;  // the phantom frame: base (600, 0, 300) mm, turned by C = 180 deg
  o.start_tip_mm[1] = -35;
  o.start_tip_mm[2] = 310;
  World w(o, "wedge_25");
  tilt_tool_about_y(w, -25.0);  // the tool's z along the wedge's normal (-sin 25, 0, cos 25)
  plant::Plant& p = *w.plant;
  EXPECT_NEAR(p.axis_normal_cosine(), 1.0, 1e-9);
  // push the coil 0.5 mm past the first touch along the axis: the flat law, along -axis
  const double axis_z = p.probe_axis()[2];
  const double s_touch = (p.site_touch().apex_z_m - p.mount_m()[2]) / axis_z;
  p.reset_state({s_touch + 0.5e-3, 0.0, 0.0});
  const double flat = plant::elastic_contact(p.contact_params(), 2.5e-3, 0.5e-3).force_N;
  EXPECT_NEAR(p.contact_force_N() / flat, 1.0, 1e-6);
  const auto f = p.contact_force_vector_N();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(f[i], -flat * p.probe_axis()[i], 1e-6 * flat) << i;
}

}  // namespace
}  // namespace palp::sim
