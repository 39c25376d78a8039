// SPDX-License-Identifier: Apache-2.0
// KUKA's ZYX pose convention (robot_bridge/pose.hpp): known rotations and round trips.
#include <gtest/gtest.h>

#include <numbers>

#include "palp/protocol/robot_bridge/pose.hpp"

namespace rb = palp::proto::rb;
constexpr double kPi = std::numbers::pi;

TEST(RobotBridgePose, AAboutZTurnsXIntoY) {
  const rb::Rotation r = rb::rotation_from_abc(kPi / 2, 0, 0);
  const double x[3] = {1, 0, 0};
  double out[3];
  rb::rotate(r, x, out);
  EXPECT_NEAR(out[0], 0, 1e-15);
  EXPECT_NEAR(out[1], 1, 1e-15);
  EXPECT_NEAR(out[2], 0, 1e-15);
}

TEST(RobotBridgePose, COfPiPointsToolZDown) {
  // the usual probe orientation: A 0, B 0, C 180 deg: tool +z is base -z
  const rb::Rotation r = rb::rotation_from_abc(0, 0, kPi);
  const double z[3] = {0, 0, 1};
  double out[3];
  rb::rotate(r, z, out);
  EXPECT_NEAR(out[2], -1, 1e-15);
}

TEST(RobotBridgePose, OrderIsZThenNewYThenNewestX) {
  // Rz(a) Ry(b) Rx(c) applied to the unit x: (cos a cos b, sin a cos b, -sin b)
  const double a = 0.3, b = -0.4, c = 1.1;
  const rb::Rotation r = rb::rotation_from_abc(a, b, c);
  EXPECT_NEAR(r.m[0][0], std::cos(a) * std::cos(b), 1e-15);
  EXPECT_NEAR(r.m[1][0], std::sin(a) * std::cos(b), 1e-15);
  EXPECT_NEAR(r.m[2][0], -std::sin(b), 1e-15);
}

TEST(RobotBridgePose, AnglesRoundTripAwayFromGimbalLock) {
  for (double a : {-3.0, -1.0, 0.0, 0.5, 3.1})
    for (double b : {-1.5, -0.2, 0.0, 0.7, 1.5})
      for (double c : {-3.1, -0.5, 0.0, 2.0, kPi}) {
        double a2, b2, c2;
        rb::abc_from_rotation(rb::rotation_from_abc(a, b, c), a2, b2, c2);
        const rb::Rotation r1 = rb::rotation_from_abc(a, b, c), r2 = rb::rotation_from_abc(a2, b2, c2);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) EXPECT_NEAR(r1.m[i][j], r2.m[i][j], 1e-12);
        EXPECT_NEAR(b2, b, 1e-12);
      }
}

TEST(RobotBridgePose, TransformTimesInverseIsIdentity) {
  rb::Transform t;
  t.r = rb::rotation_from_abc(0.2, 0.3, -2.0);
  t.t[0] = 0.5, t.t[1] = -0.1, t.t[2] = 0.3;
  const rb::Transform id = t * rb::inverse(t);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(id.t[i], 0, 1e-15);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(id.r.m[i][j], i == j ? 1 : 0, 1e-15);
  }
  const double p[3] = {0.01, 0.02, 0.03};
  double q[3], back[3];
  rb::apply(t, p, q);
  rb::apply(rb::inverse(t), q, back);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], p[i], 1e-15);
}
