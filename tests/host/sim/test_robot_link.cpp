// SPDX-License-Identifier: Apache-2.0
// palp::Robot's link handling against palp-sim's emulator (robot-bridge.md §9): a reply delayed
// past the response timeout makes the client reconnect and the command still runs exactly once;
// a dropped connection is re-established transparently; a command whose write failed is
// written again with the same seq to a restarted bridge; a frozen bridge heartbeat is a
// RobotLinkError until it moves again; a bridge that is gone is a RobotLinkError naming the URI.
#include <gmock/gmock.h>

#include <mutex>
#include <string>

#include "palp/log.hpp"

#include "test_robot_sim.hpp"

namespace {

using namespace palp::robot_test;
using palp::sim::test::SimProcess;
using testing::HasSubstr;
using testing::StartsWith;

TEST(RobotLink, AReplyDelayedPastTheTimeoutReconnectsAndTheCommandRunsOnce) {
  SimProcess sim(robot_args(), false);
  palp::RobotOptions o = fast_options();
  o.response_timeout = 200ms;
  o.watchdog = 4000ms;  // heartbeats 1 s apart: the command's own write is the delayed request
  auto robot = connect_with_probe_tool(sim, o);
  const palp::Pose start = robot->pose();
  ASSERT_EQ(sim.control("robot-reply-delay 400"), "ok");
  std::thread lift([&] {
    std::this_thread::sleep_for(700ms);
    sim.control("robot-reply-delay 0");
  });
  const auto t0 = std::chrono::steady_clock::now();
  const palp::MotionResult r = robot->move_lin_rel(palp::Pose{0.001, 0, 0, 0, 0, 0}, 0.05, 10s);
  const auto took = std::chrono::steady_clock::now() - t0;
  lift.join();
  EXPECT_GE(took, 650ms) << "the link was down until the delay was lifted";
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_EQ(r.seq, 2);
  // Once: 1 mm, not 2.
  EXPECT_POSITION_NEAR(r.final_pose, start.x_m + 0.001, start.y_m, start.z_m, 1e-6);
  const palp::RobotStatus s = robot->status();
  EXPECT_EQ(s.ack_seq, 2);
  EXPECT_EQ(s.done_seq, 2);  // not a second seq for the same command
}

TEST(RobotLink, ADroppedConnectionIsReestablishedAndCommandsGoOn) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  const palp::Pose start = robot->pose();
  std::mutex log_mu;  // the reconnect is reported through the log handler (palp/log.hpp)
  std::string log;
  palp::set_log_handler([&](palp::LogLevel level, const std::string& message) {
    std::lock_guard lock(log_mu);
    log += std::string(palp::log_level_name(level)) + ": " + message + "\n";
  });
  struct Unset {
    ~Unset() { palp::set_log_handler(nullptr); }
  } unset;
  ASSERT_EQ(sim.control("robot-drop"), "ok");
  EXPECT_POSITION_NEAR(robot->pose(), start.x_m, start.y_m, start.z_m, 1e-6);
  {
    std::lock_guard lock(log_mu);
    EXPECT_THAT(log, testing::ContainsRegex("warning: robot bridge [^ ]+: the link failed \\(.*\\): reconnecting\n"));
    EXPECT_THAT(log, testing::ContainsRegex("info: robot bridge [^ ]+ reconnected after [0-9.e+-]+ s\n"));
  }
  const palp::MotionResult r = robot->move_lin_rel(palp::Pose{0, 0.001, 0, 0, 0, 0}, 0.05, 10s);
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_EQ(r.seq, 2);
  ASSERT_EQ(sim.control("robot-drop"), "ok");
  EXPECT_EQ(robot->move_lin_rel(palp::Pose{0, -0.001, 0, 0, 0, 0}, 0.05, 10s).seq, 3);
}

TEST(RobotLink, AFrozenBridgeHeartbeatIsARobotLinkErrorUntilItMovesAgain) {
  SimProcess sim(robot_args(), false);
  auto robot = connect_with_probe_tool(sim);
  ASSERT_EQ(sim.control("robot-freeze-heartbeat on"), "ok");
  std::string error;
  const auto t0 = std::chrono::steady_clock::now();
  while (error.empty() && std::chrono::steady_clock::now() - t0 < 3s) {
    try {
      robot->status();
      std::this_thread::sleep_for(20ms);
    } catch (const palp::RobotLinkError& e) {
      error = e.what();
    }
  }
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_THAT(error, StartsWith("robot bridge heartbeat stopped: " + sim.robot_uri() +
                                " has answered with heartbeat "));
  EXPECT_GE(took, 450ms);
  EXPECT_THROW(robot->start_move_lin_rel(palp::Pose{0.001, 0, 0, 0, 0, 0}, 0.01), palp::RobotLinkError);
  ASSERT_EQ(sim.control("robot-freeze-heartbeat off"), "ok");
  bool back = false;
  const auto t1 = std::chrono::steady_clock::now();
  while (!back && std::chrono::steady_clock::now() - t1 < 3s) {
    try {
      robot->status();
      back = true;
    } catch (const palp::RobotLinkError&) {
      std::this_thread::sleep_for(20ms);
    }
  }
  EXPECT_TRUE(back) << "the client reconnects once the heartbeat moves";
  EXPECT_EQ(robot->move_lin_rel(palp::Pose{0.001, 0, 0, 0, 0, 0}, 0.05, 10s).result, rb::Result::done);
}

TEST(RobotLink, ACommandWhoseWriteFailedIsWrittenAgainWithTheSameSeqToARestartedBridge) {
  auto sim = std::make_unique<SimProcess>(robot_args(), false);
  const std::uint16_t port = sim->robot_port();
  ASSERT_NE(port, 0);
  palp::RobotOptions o = fast_options();
  o.watchdog = 10000ms;  // heartbeats 2.5 s apart: the command's own write meets the dead link
  o.reconnect_for = 3000ms;
  auto robot = connect_with_probe_tool(*sim, o);  // seq 1
  sim->stop();  // the bridge application goes away; it comes back on the same port
  std::unique_ptr<SimProcess> restarted;
  std::jthread restart([&] {  // joined however the test body ends
    std::this_thread::sleep_for(300ms);
    restarted = std::make_unique<SimProcess>(
        std::vector<std::string>{"--robot-port", std::to_string(port)}, false);
  });
  palp::MotionHandle h;
  try {
    h = robot->start_move_lin_rel(palp::Pose{-0.1, 0, 0, 0, 0, 0}, 0.5);
  } catch (const palp::Error& e) {
    FAIL() << e.what();
  }
  restart.join();
  ASSERT_TRUE(restarted && restarted->robot_port() == port);
  EXPECT_EQ(h.seq, 2);
  // Rule 6: the restarted bridge had taken nothing (ack_seq 0), so the same block went again
  // with seq 2; it ran once, from the restarted arm's start (tool 0: the flange at (600, 0,
  // 550) mm, just outside the workspace, so the move goes 100 mm towards the base).
  const palp::MotionResult r = robot->wait(h, 10s);
  EXPECT_EQ(r.result, rb::Result::done);
  EXPECT_POSITION_NEAR(r.final_pose, 0.500, 0.0, 0.550, 1e-6);
  EXPECT_EQ(robot->status().ack_seq, 2);
}

TEST(RobotLink, ABridgeThatIsGoneIsARobotLinkErrorNamingTheUriAndTheLastError) {
  SimProcess sim(robot_args(), false);
  palp::RobotOptions o = fast_options();
  o.reconnect_for = 300ms;
  auto robot = connect_with_probe_tool(sim, o);
  sim.stop();
  try {
    robot->status();
    FAIL() << "answered";
  } catch (const palp::RobotLinkError& e) {
    EXPECT_THAT(e.what(), StartsWith("robot bridge " + sim.robot_uri() + " unreachable: the link failed ("));
    EXPECT_THAT(e.what(), HasSubstr("and did not come back within 0.3"));
    EXPECT_THAT(e.what(), HasSubstr("; last error: Connection refused"));
  }
}

}  // namespace
