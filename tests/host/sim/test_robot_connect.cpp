// SPDX-License-Identifier: Apache-2.0
// palp::Robot against palp-sim's robot bridge emulator over a real Modbus TCP socket: the connect
// checks, linear moves read back to the micrometre, moves in the tool frame, rejections with
// their exact text, local checks that send nothing, a robot fault, and the host heartbeat the SDK
// keeps alive on its own.
#include <gmock/gmock.h>

#include <cmath>
#include <numbers>

#include "test_robot_sim.hpp"

namespace {

using namespace palp::robot_test;
using palp::sim::test::SimProcess;
using testing::HasSubstr;

TEST(RobotConnect, ConnectChecksIdentificationAndReadsTheStartPose) {
  SimProcess sim(robot_args(), false);
  ASSERT_NE(sim.robot_port(), 0) << sim.banner();
  auto robot = palp::connect_robot(sim.robot_uri(), fast_options());
  EXPECT_EQ(robot->info().uri, sim.robot_uri());
  EXPECT_EQ(robot->info().map_major, 1);
  EXPECT_EQ(robot->info().map_minor, 0);
  const palp::RobotStatus s = robot->status();
  EXPECT_EQ(s.state, rb::RobotState::idle);
  EXPECT_EQ(s.tool, 0);
  EXPECT_POSITION_NEAR(s.pose, 0.600, 0.0, 0.550, 1e-6);  // the flange: tool 0
  EXPECT_NEAR(std::abs(s.pose.c_rad), std::numbers::pi, 1e-5);
  std::this_thread::sleep_for(50ms);
  const palp::RobotStatus later = robot->status();
  EXPECT_NE(later.heartbeat, s.heartbeat) << "the bridge's heartbeat moves";
  EXPECT_TRUE(later.has(rb::StatusBit::host_heartbeat_ok));
}

TEST(RobotConnect, MoveLinReachesTheTargetReadBackWithinOneMicrometre) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  const palp::Pose target = offset(start, 0.0123456, -0.0054321, -0.020);
  const palp::MotionResult r = robot->move_lin(target, 0.1, 20s);
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_EQ(r.seq, 2);
  EXPECT_FALSE(r.latched.has_value());
  EXPECT_POSITION_NEAR(r.final_pose, target.x_m, target.y_m, target.z_m, 1e-6);
  EXPECT_POSITION_NEAR(robot->pose(), target.x_m, target.y_m, target.z_m, 1e-6);
}

TEST(RobotConnect, MoveLinRelMovesByTheOffsetInTheToolFrame) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  // Tool 0 is the flange, rotated by C = 180 deg: tool x = base x, tool y = base -y, tool z = base -z.
  const palp::MotionResult r = robot->move_lin_rel(palp::Pose{0.002, 0.003, 0.010, 0, 0, 0}, 0.05, 20s);
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_POSITION_NEAR(r.final_pose, start.x_m + 0.002, start.y_m - 0.003, start.z_m - 0.010, 1e-6);
}

TEST(RobotConnect, ARejectedCommandGivesItsResultNameAndMeaning) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  // Outside the emulated workspace (a sphere of 0.8 m around the base).
  try {
    robot->start_move_lin(offset(start, 0.5, 0.0, 0.0), 0.1);
    FAIL() << "accepted";
  } catch (const palp::RobotRejectedError& e) {
    EXPECT_EQ(std::string(e.what()), "robot bridge rejected move_lin (seq 2): rejected_unreachable "
                                     "— the target is outside the workspace or joint limits");
    EXPECT_EQ(e.result(), static_cast<std::uint16_t>(rb::Result::rejected_unreachable));
    EXPECT_EQ(e.register_address(), 0xFFFF);
  }
  ASSERT_EQ(sim.control("robot-reject rejected_not_ready 1"), "ok");
  try {
    robot->start_move_lin_rel(palp::Pose{0, 0, 0.001, 0, 0, 0}, 0.01);
    FAIL() << "accepted";
  } catch (const palp::RobotRejectedError& e) {
    EXPECT_EQ(std::string(e.what()), "robot bridge rejected move_lin_rel (seq 3): rejected_not_ready "
                                     "— state is not_ready or safety_stop");
  }
  // The next command is carried out, with the next seq.
  EXPECT_EQ(robot->move_lin_rel(palp::Pose{0, 0, 0.001, 0, 0, 0}, 0.01, 20s).seq, 4);
}

TEST(RobotConnect, ACommandRefusedLocallySendsNothing) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  EXPECT_THROW(robot->start_move_lin(start, 2.0), palp::ConfigError);  // 2 m/s
  palp::GuardedApproach g;
  g.max_travel_m = 0.0;
  EXPECT_THROW(robot->start_guarded_approach(g), palp::ConfigError);
  EXPECT_THROW(robot->set_tool(16, palp::Pose{}), palp::ConfigError);
  EXPECT_EQ(robot->status().ack_seq, 1) << "nothing reached the bridge after set_tool";
  EXPECT_EQ(robot->move_lin_rel(palp::Pose{0, 0, 0.001, 0, 0, 0}, 0.01, 20s).seq, 2);
}

TEST(RobotConnect, ARobotFaultEndsTheMotionWithRobotFaultErrorAndResetFaultRecovers) {
  SimProcess sim(robot_args(), false);
  // Real time (set before connecting: palp-sim paces from the client's connect), so the motion
  // is still running when it faults.
  ASSERT_EQ(sim.control("pace 1"), "ok");
  auto robot = connect_with_probe_tool(sim);
  const palp::MotionHandle h = robot->start_move_lin_rel(palp::Pose{0.05, 0, 0, 0, 0, 0}, 0.01);
  std::this_thread::sleep_for(100ms);
  ASSERT_EQ(sim.control("robot-fault"), "ok");
  try {
    robot->wait(h, 10s);
    FAIL() << "no fault";
  } catch (const palp::RobotFaultError& e) {
    EXPECT_EQ(std::string(e.what()), "robot bridge: move_lin_rel (seq 2) ended with robot_fault — a "
                                     "robot error ended the motion; state is faulted");
    EXPECT_EQ(e.result(), static_cast<std::uint16_t>(rb::Result::robot_fault));
  }
  EXPECT_EQ(robot->status().state, rb::RobotState::faulted);
  try {
    robot->start_move_lin_rel(palp::Pose{0.001, 0, 0, 0, 0, 0}, 0.01);
    FAIL() << "accepted while faulted";
  } catch (const palp::RobotRejectedError& e) {
    EXPECT_THAT(e.what(), HasSubstr("rejected_faulted"));
  }
  robot->reset_fault();
  EXPECT_EQ(robot->status().state, rb::RobotState::idle);
}

TEST(RobotConnect, TheSdkKeepsTheHostHeartbeatAliveIdleAndThroughATwoSecondMotionWithA200msWatchdog) {
  SimProcess sim(robot_args(), false);
  ASSERT_EQ(sim.control("pace 1"), "ok");  // virtual = wall time: the motion lasts ~2 s
  palp::RobotOptions o = fast_options();
  o.watchdog = 200ms;
  auto robot = connect_with_probe_tool(sim, o);
  std::this_thread::sleep_for(600ms);  // idle, three watchdog periods without a call
  palp::RobotStatus idle = robot->status();
  EXPECT_TRUE(idle.has(rb::StatusBit::host_heartbeat_ok));
  const palp::Pose start = idle.pose;
  const auto t0 = std::chrono::steady_clock::now();
  // 19 mm at 10 mm/s with 0.5 m/s^2 ramps: 1.92 s.
  const palp::MotionResult r = robot->move_lin_rel(palp::Pose{0.019, 0, 0, 0, 0, 0}, 0.01, 10s);
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_EQ(r.result, rb::Result::done) << "not watchdog";
  EXPECT_GE(took, 1800ms);
  EXPECT_POSITION_NEAR(r.final_pose, start.x_m + 0.019, start.y_m, start.z_m, 1e-6);
  const palp::RobotStatus s = robot->status();
  EXPECT_TRUE(s.has(rb::StatusBit::host_heartbeat_ok));
  EXPECT_FALSE(s.has(rb::StatusBit::watchdog_tripped));
}

}  // namespace
