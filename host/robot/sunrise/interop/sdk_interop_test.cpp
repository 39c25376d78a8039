// SPDX-License-Identifier: Apache-2.0
// The SDK's Modbus robot client (palp::connect_robot, libmodbus) against the Java bridge core
// (ModbusTcpServer + BridgeCore of host/robot/sunrise) with a simulated arm (LoopbackBridge): two
// independent implementations of protocol/robot-bridge.md over a real loopback socket. The
// simulated arm starts at z 300 mm, tool = base orientation, moves in straight lines at the
// commanded speed, brakes 10 ms after a stop, and meets a 1 N/mm plate at z 310 mm. It moves on
// the bridge's cycles (5 ms of arm time per cycle, LoopbackBridge), so its distances are exact
// however late the JVM runs a cycle; the bridge's watchdog and these tests' timeouts are on the
// wall clock.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <numbers>
#include <cstdio>
#include <string>
#include <thread>

#include "palp/error.hpp"
#include "palp/robot.hpp"

namespace {

namespace rb = palp::proto::rb;
using namespace std::chrono_literals;

/// LoopbackBridge in a child JVM on an ephemeral port; killed at the end of the test.
class JavaBridge {
 public:
  JavaBridge() {
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe failed");
    pid_ = fork();
    if (pid_ == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      close(out[1]);
      execl(PALP_JAVA, PALP_JAVA, "-cp", PALP_SUNRISE_CLASSPATH, "org.palp.bridge.LoopbackBridge",
            "--ignore-stdin", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(out[1]);
    FILE* f = fdopen(out[0], "r");
    char line[64] = {};
    if (f == nullptr || std::fgets(line, sizeof line, f) == nullptr || std::sscanf(line, "port %d", &port_) != 1)
      port_ = 0;
    if (f != nullptr) std::fclose(f);
  }
  ~JavaBridge() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
  }
  JavaBridge(const JavaBridge&) = delete;
  JavaBridge& operator=(const JavaBridge&) = delete;
  std::string uri() const { return "modbus://127.0.0.1:" + std::to_string(port_); }
  int port() const { return port_; }

 private:
  pid_t pid_ = -1;
  int port_ = 0;
};

class SdkAgainstJavaBridge : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_NE(bridge.port(), 0) << "LoopbackBridge did not print its port"; }
  JavaBridge bridge;
};

TEST_F(SdkAgainstJavaBridge, ConnectReadsMapOneZeroAndTheSimulatedArmsStatus) {
  auto robot = palp::connect_robot(bridge.uri());
  EXPECT_EQ(robot->info().map_major, 1);
  EXPECT_EQ(robot->info().map_minor, 0);
  const palp::RobotStatus s = robot->status();
  EXPECT_EQ(s.state, rb::RobotState::idle);
  EXPECT_TRUE(s.has(rb::StatusBit::drives_enabled));
  EXPECT_FALSE(s.has(rb::StatusBit::automatic_mode));
  EXPECT_NEAR(s.pose.z_m, 0.300, 1e-9);
  EXPECT_NEAR(s.joints_rad[1], 30.0 * std::numbers::pi / 180.0, 1e-9);
  EXPECT_NEAR(s.joints_rad[6], -45.0 * std::numbers::pi / 180.0, 1e-9);
}

TEST_F(SdkAgainstJavaBridge, MoveLinRelRunsToItsTargetAndFinishesDone) {
  auto robot = palp::connect_robot(bridge.uri());
  palp::Pose offset;
  offset.z_m = 0.005;
  const palp::MotionResult r = robot->move_lin_rel(offset, 0.05, 5s);
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_NEAR(r.final_pose.z_m, 0.305, 1e-6);
}

TEST_F(SdkAgainstJavaBridge, GuardedApproachStopsOnTheForceGuardTwoNewtonsIntoThePlate) {
  auto robot = palp::connect_robot(bridge.uri());
  palp::GuardedApproach g;
  g.axis = rb::Axis::tool_z;
  g.speed_m_per_s = 0.02;
  g.max_travel_m = 0.02;
  g.guard_host_stop = false;
  g.force_threshold_N = 2.0;
  const palp::MotionResult r = robot->wait(robot->start_guarded_approach(g), 5s);
  EXPECT_EQ(r.result, rb::Result::guard_fired);
  EXPECT_EQ(r.guard_fired, rb::bit(rb::GuardSource::force));
  ASSERT_TRUE(r.latched.has_value());
  // 2 N on the 1 N/mm plate at 310 mm: 312 mm, plus up to one cycle's travel (0.1 mm per 5 ms)
  EXPECT_GE(r.latched->z_m, 0.312 - 1e-6);
  EXPECT_LE(r.latched->z_m, 0.313);
  // the simulated arm brakes 10 ms after the stop: 0.2 mm at 20 mm/s
  EXPECT_NEAR(r.final_pose.z_m - r.latched->z_m, 0.0002, 0.00002);
  const palp::RobotStatus s = robot->status();
  ASSERT_TRUE(s.force_N.has_value());
  EXPECT_NEAR(*s.force_N, (s.pose.z_m - 0.310) * 1000.0, 0.002);  // 1 N/mm at rest
}

TEST_F(SdkAgainstJavaBridge, StopMidMoveReturnsStationaryAndTheMotionEndsStopped) {
  auto robot = palp::connect_robot(bridge.uri());
  palp::Pose offset;
  offset.z_m = -0.02;
  const palp::MotionHandle h = robot->start_move_lin_rel(offset, 0.02);
  // until it has moved 1 mm (50 ms of the arm's time; the wall time it takes depends on the load)
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (robot->status().pose.z_m > 0.299 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(5ms);
  const palp::RobotStatus s = robot->stop();
  EXPECT_EQ(s.state, rb::RobotState::idle);
  const palp::MotionResult r = robot->wait(h, 2s);
  EXPECT_EQ(r.result, rb::Result::stopped);
  ASSERT_TRUE(r.latched.has_value());
  EXPECT_LT(r.final_pose.z_m, 0.300 - 0.001);  // it moved before the stop
  EXPECT_NEAR(r.latched->z_m - r.final_pose.z_m, 0.0002, 0.00002);  // 10 ms at 20 mm/s
}

TEST_F(SdkAgainstJavaBridge, SetToolWhileMovingIsRejectedBusyByTheBridge) {
  auto robot = palp::connect_robot(bridge.uri());
  palp::Pose offset;
  offset.z_m = -0.02;
  robot->start_move_lin_rel(offset, 0.02);
  try {
    robot->set_tool(1, palp::Pose{});
    FAIL() << "set_tool while moving was accepted";
  } catch (const palp::RobotRejectedError& e) {
    EXPECT_EQ(e.result(), static_cast<std::uint16_t>(rb::Result::rejected_busy));
    EXPECT_NE(std::string(e.what()).find("rejected_busy"), std::string::npos) << e.what();
  }
  robot->stop();
}

}  // namespace
