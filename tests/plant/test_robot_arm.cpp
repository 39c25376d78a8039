// SPDX-License-Identifier: Apache-2.0
// RobotArm: trapezoidal linear motion, braking, tools, workspace (known answers).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "palp/plant/robot_arm.hpp"

namespace palp::plant {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 50e-6;

// Flange 0.5 m in front of the base, 0.4 m up, pointing down (C = 180 deg).
Transform start_pose() { return pose_from_xyzabc(0.5, 0.0, 0.4, 0, 0, kPi); }

double run_until_still(RobotArm& arm, double limit_s = 10.0) {
  double t = 0;
  while (arm.moving() && t < limit_s) {
    arm.step(kDt);
    t += kDt;
  }
  return t;
}

TEST(RobotArm, TrapezoidTakesLengthOverSpeedPlusSpeedOverAccel) {
  RobotArm arm(start_pose());
  Transform target = start_pose();
  target.t[0] += 0.1;  // 100 mm at 50 mm/s, a = 0.5: t = 0.1/0.05 + 0.05/0.5 = 2.1 s
  ASSERT_TRUE(arm.move_lin(target, 0.05));
  const double t = run_until_still(arm);
  EXPECT_NEAR(t, 2.1, 2 * kDt);
  EXPECT_TRUE(arm.reached_target());
  EXPECT_NEAR(arm.tcp().t[0], 0.6, 1e-12);
  EXPECT_NEAR(arm.tcp().t[2], 0.4, 1e-12);
}

TEST(RobotArm, ShortMoveIsATriangleOfTwiceSqrtLengthOverAccel) {
  RobotArm arm(start_pose());
  Transform target = start_pose();
  target.t[1] += 0.002;  // 2 mm at 1 m/s never cruises: t = 2 sqrt(0.002 / 0.5) = 0.12649 s
  ASSERT_TRUE(arm.move_lin(target, 1.0));
  EXPECT_NEAR(run_until_still(arm), 2 * std::sqrt(0.002 / 0.5), 2 * kDt);
  EXPECT_NEAR(arm.tcp().t[1], 0.002, 1e-12);
}

TEST(RobotArm, AccelerationPhaseCoversHalfATSquared) {
  RobotArm arm(start_pose());
  Transform target = start_pose();
  target.t[2] -= 0.1;
  ASSERT_TRUE(arm.move_lin(target, 0.1));
  for (int k = 0; k < 2000; ++k) arm.step(kDt);  // 0.1 s, within the 0.2 s ramp
  EXPECT_NEAR(arm.speed_m_per_s(), 0.05, 1e-9);
  EXPECT_NEAR(arm.travelled_m(), 0.5 * 0.5 * 0.1 * 0.1, 1e-9);
  EXPECT_NEAR(arm.tcp().t[2], 0.4 - 0.0025, 1e-9);
}

TEST(RobotArm, StopBrakesWithinLatencyTimesSpeedPlusVSquaredOverTwiceDecel) {
  RobotArm arm(start_pose());
  Transform target = start_pose();
  target.t[1] += 0.2;
  ASSERT_TRUE(arm.move_lin(target, 0.1));
  for (int k = 0; k < 10000; ++k) arm.step(kDt);  // 0.5 s: cruising at 0.1 m/s
  ASSERT_NEAR(arm.speed_m_per_s(), 0.1, 1e-12);
  const double at_stop = arm.travelled_m();
  arm.stop();
  run_until_still(arm);
  // 0.1 m/s x 4 ms + 0.01 / (2 x 2) = 0.4 mm + 2.5 mm
  EXPECT_NEAR(arm.travelled_m() - at_stop, 0.0004 + 0.0025, 1e-9);
  EXPECT_FALSE(arm.reached_target());
  EXPECT_FALSE(arm.moving());
}

TEST(RobotArm, StopNearTheEndStillEndsAtTheTargetNotBeyond) {
  RobotArm arm(start_pose());
  Transform target = start_pose();
  target.t[0] += 0.01;
  ASSERT_TRUE(arm.move_lin(target, 0.01));  // 1.02 s
  for (int k = 0; k < 20390; ++k) arm.step(kDt);
  arm.stop();
  run_until_still(arm);
  EXPECT_NEAR(arm.tcp().t[0], 0.51, 1e-12);
  EXPECT_TRUE(arm.reached_target());
}

TEST(RobotArm, TargetsOutsideTheSphereOrBelowTheBaseAreUnreachable) {
  RobotArm arm(start_pose());
  EXPECT_FALSE(arm.move_lin(pose_from_xyzabc(0.7, 0.0, 0.5, 0, 0, kPi), 0.1));  // 0.86 m
  EXPECT_FALSE(arm.move_lin(pose_from_xyzabc(0.5, 0.0, -0.001, 0, 0, kPi), 0.1));
  EXPECT_FALSE(arm.moving());
  EXPECT_TRUE(arm.reachable(pose_from_xyzabc(0.8, 0.0, 0.0, 0, 0, 0)));
  EXPECT_FALSE(arm.reachable(pose_from_xyzabc(0.8, 0.0001, 0.0, 0, 0, 0)));
  EXPECT_TRUE(arm.move_lin(pose_from_xyzabc(0.5, 0.0, 0.0, 0, 0, kPi), 0.1));
}

TEST(RobotArm, ToolMovesTheTcpAndRelativeMovesAreInTheToolFrame) {
  RobotArm arm(start_pose());
  Transform probe;  // 200 mm along the flange's z
  probe.t[2] = 0.2;
  ASSERT_TRUE(arm.set_tool(probe));
  EXPECT_NEAR(arm.tcp().t[2], 0.2, 1e-12);  // flange points down: the tip is 0.2 m lower
  Transform down;  // +10 mm along the tool's z: down in the base frame
  down.t[2] = 0.01;
  ASSERT_TRUE(arm.move_lin_rel(down, 0.05));
  EXPECT_FALSE(arm.set_tool(Transform{}));  // not while moving
  run_until_still(arm);
  EXPECT_NEAR(arm.tcp().t[2], 0.19, 1e-12);
  EXPECT_NEAR(arm.flange().t[2], 0.39, 1e-12);
}

TEST(RobotArm, OrientationIsInterpolatedAndReachesTheTarget) {
  RobotArm arm(start_pose());
  const Transform target = pose_from_xyzabc(0.5, 0.0, 0.4, kPi / 2, 0, kPi);
  ASSERT_TRUE(arm.move_lin(target, 0.1));  // 90 deg counts as 0.157 m of path
  for (int k = 0; k < 20; ++k) arm.step(kDt);
  ASSERT_TRUE(arm.moving());
  run_until_still(arm);
  double a, b, c;
  proto::rb::abc_from_rotation(arm.tcp().r, a, b, c);
  EXPECT_NEAR(a, kPi / 2, 1e-9);
  EXPECT_NEAR(b, 0, 1e-9);
  EXPECT_NEAR(std::abs(c), kPi, 1e-9);
}

TEST(RobotArm, PtpMovesAtPermilleOfItsMaximumSpeed) {
  RobotArm arm(start_pose());
  Transform target = start_pose();
  target.t[0] += 0.1;
  ASSERT_TRUE(arm.move_ptp(target, 50));  // 0.05 m/s: as the 2.1 s linear move
  EXPECT_NEAR(run_until_still(arm), 2.1, 2 * kDt);
}

}  // namespace
}  // namespace palp::plant
