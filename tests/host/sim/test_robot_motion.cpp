// SPDX-License-Identifier: Apache-2.0
// Guarded approach and stop through palp::Robot against palp-sim's emulator: the force guard
// stops the arm on the solid_1d phantom where the tip has indented it, and a stop in the middle
// of a motion returns the pose latched when it was taken, short of where the arm came to rest;
// hold supersedes a motion; move_ptp reaches its target.
#include <gmock/gmock.h>

#include "test_robot_sim.hpp"

namespace {

using namespace palp::robot_test;
using palp::sim::test::SimProcess;

TEST(RobotMotion, GuardedApproachStopsOnTheForceGuardOnTheSolidPhantom) {
  SimProcess sim(robot_args({"--phantom", "solid_1d"}), false);
  auto robot = connect_with_probe_tool(sim);
  palp::RobotStatus s = robot->status();
  EXPECT_EQ(s.tool, 1);
  EXPECT_POSITION_NEAR(s.pose, 0.600, 0.0, 0.350, 1e-6);  // the tip, 50 mm above the phantom
  // Above position 3 of the bar (phantom x = 27 mm), 5 mm above its top (base z = 300 mm).
  robot->move_lin(palp::Pose{0.627, 0.0, 0.305, s.pose.a_rad, s.pose.b_rad, s.pose.c_rad}, 0.05, 20s);

  palp::GuardedApproach g;  // along the tool's +z: into the phantom
  g.speed_m_per_s = 2e-3;
  g.max_travel_m = 0.015;
  g.force_threshold_N = 0.5;
  const palp::MotionResult r = robot->wait(robot->start_guarded_approach(g), 30s);
  EXPECT_EQ(r.result, rb::Result::guard_fired);
  EXPECT_EQ(r.guard_fired, rb::bit(rb::GuardSource::force));
  ASSERT_TRUE(r.latched.has_value());
  // Contact starts at z = 300 mm. 0.5 N indents the 15 mm layer (E* 125.8 kPa) by less than a
  // half-space would (Hertz: 1.53 mm with R = 2.5 mm) and by more than 0.5 mm.
  EXPECT_GT(r.latched->z_m, 0.300 - 1.53e-3);
  EXPECT_LT(r.latched->z_m, 0.300 - 0.5e-3);
  EXPECT_NEAR(r.latched->x_m, 0.627, 1e-6);
  // At rest past the latch by the emulator's stop latency and braking (4 ms and 2 m/s^2 at
  // 2 mm/s: 8 + 1 um), along the approach (base -z).
  EXPECT_NEAR(r.latched->z_m - r.final_pose.z_m, 9e-6, 3e-6);
  s = robot->status();
  ASSERT_TRUE(s.force_N.has_value());
  EXPECT_GT(*s.force_N, 0.1);  // still pressing on the phantom at rest (noise 0.05 N)
}

TEST(RobotMotion, GuardedApproachWithoutContactEndsAtMaxTravel) {
  SimProcess sim(robot_args({"--phantom", "solid_1d"}), false);
  auto robot = connect_with_probe_tool(sim);
  palp::GuardedApproach g;
  g.speed_m_per_s = 0.01;
  g.max_travel_m = 0.010;  // 10 mm of the 50 mm to the phantom
  g.force_threshold_N = 0.5;
  const palp::MotionResult r = robot->wait(robot->start_guarded_approach(g), 30s);
  EXPECT_EQ(r.result, rb::Result::max_travel);
  EXPECT_FALSE(r.latched.has_value());
  EXPECT_POSITION_NEAR(r.final_pose, 0.600, 0.0, 0.340, 1e-6);
}

TEST(RobotMotion, StopMidMotionReturnsThePoseLatchedWhenItWasTaken) {
  SimProcess sim(robot_args(), false);
  ASSERT_EQ(sim.control("pace 1"), "ok");  // real time, so the stop lands mid-motion
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  const palp::MotionHandle h = robot->start_move_lin_rel(palp::Pose{0.05, 0, 0, 0, 0, 0}, 0.01);
  std::this_thread::sleep_for(300ms);
  const palp::RobotStatus stopped = robot->stop();
  ASSERT_TRUE(stopped.latched.has_value());
  EXPECT_GT(stopped.latched->x_m, start.x_m + 0.0005);
  EXPECT_LT(stopped.latched->x_m, start.x_m + 0.045);  // before the 50 mm target
  const palp::MotionResult r = robot->wait(h, 5s);
  EXPECT_EQ(r.result, rb::Result::stopped);
  ASSERT_TRUE(r.latched.has_value());
  EXPECT_DOUBLE_EQ(r.latched->x_m, stopped.latched->x_m);
  // At rest past the latch by the emulator's stop latency and braking (4 ms and 2 m/s^2 at
  // 10 mm/s: 40 + 25 um).
  EXPECT_NEAR(r.final_pose.x_m - r.latched->x_m, 65e-6, 3e-6);
  EXPECT_NEAR(r.final_pose.y_m, start.y_m, 1e-6);
  // A stop while stationary is seen at once and does not touch the finished result.
  const palp::RobotStatus again = robot->stop();
  EXPECT_EQ(again.done_seq, h.seq);
  EXPECT_EQ(again.result, rb::Result::stopped);
}

}  // namespace

namespace {

TEST(RobotMotion, HoldEndsARunningMotionAsSupersededAndHoldsThePose) {
  SimProcess sim(robot_args(), false);
  ASSERT_EQ(sim.control("pace 1"), "ok");  // real time, so the hold lands mid-motion
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  const palp::MotionHandle h = robot->start_move_lin_rel(palp::Pose{0.05, 0, 0, 0, 0, 0}, 0.01);
  std::this_thread::sleep_for(200ms);
  robot->hold();
  const palp::MotionResult r = robot->wait(h, 5s);
  EXPECT_EQ(r.result, rb::Result::superseded);
  EXPECT_FALSE(r.latched.has_value());
  EXPECT_GT(r.final_pose.x_m, start.x_m + 0.0005);
  EXPECT_LT(r.final_pose.x_m, start.x_m + 0.045);
  const palp::RobotStatus s = robot->status();
  EXPECT_EQ(s.state, rb::RobotState::idle);
  EXPECT_EQ(s.done_seq, h.seq + 1) << "the hold itself finished";
  EXPECT_NEAR(s.pose.x_m, r.final_pose.x_m, 1e-6);
}

TEST(RobotMotion, MovePtpReachesItsTargetWithASpeedFraction) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose target = offset(robot->pose(), -0.010, 0.020, 0.005);
  const palp::MotionResult r = robot->wait(robot->start_move_ptp(target, 0.25), 20s);
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_POSITION_NEAR(r.final_pose, target.x_m, target.y_m, target.z_m, 1e-6);
}

}  // namespace
