// SPDX-License-Identifier: Apache-2.0
// palp-sim with the robot bridge emulator on (--robot-port 0), for the robot client's tests: the
// device socket is left alone (the robot client alone keeps virtual time running), the arm starts
// with the flange at base (600, 0, 550) mm pointing down (C = 180 deg), the probe tip 50 mm above
// the phantom origin at base (600, 0, 300) mm (phantom +z = base -z).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "palp/error.hpp"
#include "palp/robot.hpp"
#include "sim_process.hpp"

namespace palp::robot_test {

using namespace std::chrono_literals;
namespace rb = proto::rb;

inline std::vector<std::string> robot_args(std::vector<std::string> extra = {}) {
  std::vector<std::string> a = {"--robot-port", "0"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

/// Fast options for tests: a short response timeout and reconnect window.
inline RobotOptions fast_options() {
  RobotOptions o;
  o.response_timeout = 300ms;
  o.reconnect_for = 2000ms;
  o.status_period = 5ms;
  return o;
}

/// The probe's tip apex (stroke origin) on the flange: 200 mm along the flange's +z.
inline const Pose kProbeTcp{0.0, 0.0, 0.200, 0.0, 0.0, 0.0};

/// Connects and makes the probe tip the TCP (tool 1, seq 1): the tip starts at base
/// (600, 0, 350) mm, inside the emulator's workspace (0.8 m around the base; the flange at
/// (600, 0, 550) mm is not).
inline std::unique_ptr<Robot> connect_with_probe_tool(const sim::test::SimProcess& sim,
                                                      RobotOptions o = fast_options()) {
  auto robot = connect_robot(sim.robot_uri(), o);
  robot->set_tool(1, kProbeTcp);
  return robot;
}

inline Pose offset(const Pose& p, double dx, double dy, double dz) {
  Pose q = p;
  q.x_m += dx;
  q.y_m += dy;
  q.z_m += dz;
  return q;
}

#define EXPECT_POSITION_NEAR(p, x, y, z, tol) \
  do {                                          \
    EXPECT_NEAR((p).x_m, (x), (tol));           \
    EXPECT_NEAR((p).y_m, (y), (tol));           \
    EXPECT_NEAR((p).z_m, (z), (tol));           \
  } while (0)

}  // namespace palp::robot_test
