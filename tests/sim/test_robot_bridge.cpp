// SPDX-License-Identifier: Apache-2.0
// RobotBridge driven directly (no sockets): the §8 handshake, the cycle, rejections, guards, the
// watchdog and the Modbus access rules of protocol/robot-bridge.md, with exact registers.
#include <gtest/gtest.h>

#include <array>
#include <numbers>

#include "palp/sim/robot_bridge.hpp"

namespace palp::sim {
namespace {

using rb::Axis;
using rb::CommandCode;
using rb::Result;
using rb::RobotState;
using rb::StatusBit;

constexpr double kPi = std::numbers::pi;
constexpr rb::u16 kOk = rb::bit(StatusBit::drives_enabled) | rb::bit(StatusBit::automatic_mode) |
                        rb::bit(StatusBit::host_heartbeat_ok);

struct Rig {
  // flange 0.5 m in front, 0.4 m up, pointing down; tool 0 (the flange)
  plant::RobotArm arm{plant::pose_from_xyzabc(0.5, 0.0, 0.4, 0, 0, kPi)};
  RobotBridge bridge{arm, [] {
                       RobotBridgeOptions o;
                       o.force_noise_N = 0;
                       return o;
                     }()};
  std::uint64_t wall_us = 1'000'000;
  rb::u16 hb = 0, stop = 0;
  bool keep_alive = true;
  // force on the TCP as a function of its z (a wall below z_wall, stiffness in N/m)
  double z_wall = -1, k_wall = 0;

  void run_ms(int ms) {
    for (int k = 0; k < ms; ++k) {
      if (keep_alive && k % 100 == 0) heartbeat();
      wall_us += 1000;
      const double z = arm.tcp().t[2];
      const double f[3] = {0, 0, z < z_wall ? k_wall * (z_wall - z) : 0.0};
      bridge.set_external_force(f, true);
      bridge.advance(1e-3, wall_us);
    }
  }
  void heartbeat() {
    const rb::u16 v[1] = {++hb};
    ASSERT_EQ(bridge.write(200, v, true), ModbusException::none);
  }
  void request_stop() {
    const rb::u16 v[1] = {++stop};
    ASSERT_EQ(bridge.write(201, v, true), ModbusException::none);
  }
  ModbusException commit(const rb::Command& c) {
    std::array<rb::u16, rb::Command::kLength> r{};
    rb::encode(c, std::span<rb::u16, rb::Command::kLength>(r));
    return bridge.write(300, r, false);
  }
  const rb::StatusBlock& st() const { return bridge.status(); }
};

rb::Command move_lin_rel(rb::u16 seq, rb::i32 dz_um, rb::i32 speed) {
  rb::Command c{};
  c.seq = seq;
  c.code = CommandCode::move_lin_rel;
  c.speed = speed;
  c.z_um = dz_um;
  return c;
}

rb::Command approach(rb::u16 seq, rb::u16 guards, rb::i32 speed, rb::i32 travel) {
  rb::Command c{};
  c.seq = seq;
  c.code = CommandCode::guarded_approach;
  c.guard_sources = guards;
  c.axis = Axis::tool_z;
  c.speed = speed;
  c.max_travel_um = travel;
  if (guards & rb::bit(rb::GuardSource::force)) c.force_threshold_mN = 2000;
  if (guards & rb::bit(rb::GuardSource::digital_input)) c.digital_input = 1;
  return c;
}

TEST(RobotBridge, StartsIdleWithTheSpecsInitialRegisters) {
  Rig r;
  r.run_ms(1);
  EXPECT_EQ(r.st().state, RobotState::idle);
  EXPECT_EQ(r.st().ack_seq, 0);
  EXPECT_EQ(r.st().done_seq, 0);
  EXPECT_EQ(r.st().result, Result::none);
  EXPECT_EQ(r.st().x_um, 500000);
  EXPECT_EQ(r.st().z_um, 400000);
  EXPECT_EQ(r.st().c_mdeg, 180000);
  rb::u16 ctl[3];
  ASSERT_EQ(r.bridge.read(200, 3, ctl), ModbusException::none);
  EXPECT_EQ(ctl[2], 500);  // watchdog_ms until written
  rb::u16 id[10];
  ASSERT_EQ(r.bridge.read(0, 10, id), ModbusException::none);
  const rb::u16 expected[10] = {0x5041, 0x4c50, 1, 0, 100, 53, 200, 3, 300, 24};
  for (int k = 0; k < 10; ++k) EXPECT_EQ(id[k], expected[k]) << k;
}

TEST(RobotBridge, HeartbeatCountsEveryCycleAndRobotTimeIsVirtualMs) {
  Rig r;
  r.run_ms(10);
  const rb::u16 hb0 = r.st().heartbeat;
  EXPECT_EQ(r.st().robot_time_ms, 10u);
  r.run_ms(25);
  EXPECT_EQ(r.st().heartbeat, hb0 + 25);
  EXPECT_EQ(r.st().robot_time_ms, 35u);
  r.bridge.freeze_heartbeat(true);
  r.run_ms(5);
  EXPECT_EQ(r.st().heartbeat, hb0 + 25);
}

TEST(RobotBridge, TheCyclePeriodIsAKnob) {
  plant::RobotArm arm{plant::pose_from_xyzabc(0.5, 0.0, 0.4, 0, 0, kPi)};
  RobotBridgeOptions o;
  o.cycle_ms = 2.0;
  RobotBridge bridge{arm, o};
  const rb::u16 hb0 = bridge.status().heartbeat;
  for (int k = 0; k < 200; ++k) bridge.advance(50e-6, 0);  // 10 ms of 50 us ticks
  EXPECT_EQ(bridge.status().heartbeat, hb0 + 6);  // the first tick, then 2, 4, 6, 8, 10 ms
  EXPECT_EQ(bridge.status().robot_time_ms, 10u);  // the last snapshot's time
}

// §8.2: a guarded approach stopped by the force guard, then a stop racing a finished retreat.
TEST(RobotBridge, TimelineOfSection8_2GivesTheExactStatusAfterEachStep) {
  Rig r;
  r.z_wall = 0.39;  // 10 mm below the start, 500 N/m: 2 N at 4 mm in
  r.k_wall = 500;
  r.run_ms(10);
  EXPECT_EQ(r.st().status_bits, kOk | rb::bit(StatusBit::force_valid));
  ASSERT_EQ(r.commit(approach(42, 0x0005, 2000, 20000)), ModbusException::none);
  r.run_ms(1);
  EXPECT_EQ(r.st().state, RobotState::moving);
  EXPECT_EQ(r.st().ack_seq, 42);
  EXPECT_EQ(r.st().ack_result, Result::accepted);
  EXPECT_EQ(r.st().done_seq, 0);
  int ms = 0;
  while (r.st().state == RobotState::moving && ms < 20000) r.run_ms(1), ++ms;
  EXPECT_EQ(r.st().state, RobotState::idle);
  EXPECT_EQ(r.st().done_seq, 42);
  EXPECT_EQ(r.st().result, Result::guard_fired);
  EXPECT_EQ(r.st().guard_fired, 0x0004);
  EXPECT_EQ(r.st().status_bits, kOk | rb::bit(StatusBit::latched_pose_valid) |
                                    rb::bit(StatusBit::force_valid));
  // latched where the force reached 2 N: 4 mm into the wall (one 1 ms cycle = 2 um of slack)
  EXPECT_NEAR(r.st().latched_z_um, 386000, 3);
  // then 2 mm/s x 4 ms latency + (2 mm/s)^2 / (2 x 2 m/s^2) = 8 um + 1 um of braking
  EXPECT_NEAR(r.st().latched_z_um - r.st().z_um, 9, 1);
  EXPECT_GE(r.st().force_mN, 2000);
  EXPECT_EQ(r.st().stop_seen, 0);

  // retreat 5 mm up (tool -z) at 10 mm/s: 0.5 s + 0.02 s
  ASSERT_EQ(r.commit(move_lin_rel(43, -5000, 10000)), ModbusException::none);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_seq, 43);
  EXPECT_EQ(r.st().ack_result, Result::accepted);
  EXPECT_EQ(r.st().state, RobotState::moving);
  while (r.st().state == RobotState::moving) r.run_ms(1);
  // the host's stop arrives after the retreat finished: it keeps `done` (rule 8)
  const rb::i32 z_rest = r.st().z_um;
  r.request_stop();
  r.run_ms(1);
  EXPECT_EQ(r.st().done_seq, 43);
  EXPECT_EQ(r.st().result, Result::done);
  EXPECT_EQ(r.st().guard_fired, 0);
  EXPECT_EQ(r.st().stop_seen, 1);
  EXPECT_EQ(r.st().latched_z_um, z_rest);
}

TEST(RobotBridge, StopDuringAMoveLatchesAndSetsStopSeenOnlyOnceStationary) {
  Rig r;
  rb::Command c{};
  c.seq = 1;
  c.code = CommandCode::move_lin;
  c.speed = 100000;  // 100 mm/s
  c.x_um = 500000, c.y_um = 200000, c.z_um = 400000, c.c_mdeg = 180000;
  ASSERT_EQ(r.commit(c), ModbusException::none);
  r.run_ms(500);  // cruising at 0.1 m/s
  r.request_stop();
  r.run_ms(1);
  const rb::i32 latched_y = r.st().latched_y_um;
  EXPECT_EQ(r.st().state, RobotState::moving);  // braking: 4 ms + 50 ms
  EXPECT_EQ(r.st().stop_seen, 0);
  EXPECT_EQ(r.st().done_seq, 0);
  r.run_ms(60);
  EXPECT_EQ(r.st().state, RobotState::idle);
  EXPECT_EQ(r.st().done_seq, 1);
  EXPECT_EQ(r.st().result, Result::stopped);
  EXPECT_EQ(r.st().stop_seen, 1);
  EXPECT_NEAR(r.st().y_um - latched_y, 400 + 2500, 101);  // v*latency + v^2/2b, 1 cycle slack
}

TEST(RobotBridge, HostStopGuardEndsAnApproachAsGuardFired) {
  Rig r;
  ASSERT_EQ(r.commit(approach(1, 0x0001, 5000, 20000)), ModbusException::none);
  r.run_ms(100);
  r.request_stop();
  r.run_ms(20);
  EXPECT_EQ(r.st().result, Result::guard_fired);
  EXPECT_EQ(r.st().guard_fired, 0x0001);
  EXPECT_EQ(r.st().stop_seen, 1);
}

TEST(RobotBridge, StopDuringAnApproachWithoutHostStopEndsItStopped) {
  Rig r;
  ASSERT_EQ(r.commit(approach(1, 0x0004, 5000, 20000)), ModbusException::none);
  r.run_ms(100);
  r.request_stop();
  r.run_ms(20);
  EXPECT_EQ(r.st().result, Result::stopped);
  EXPECT_EQ(r.st().guard_fired, 0);
}

TEST(RobotBridge, DigitalInputGuardFiresOnTheWiredInput) {
  Rig r;
  ASSERT_EQ(r.commit(approach(1, 0x0002, 5000, 20000)), ModbusException::none);
  r.run_ms(50);
  EXPECT_EQ(r.st().state, RobotState::moving);
  r.bridge.set_digital_inputs(0x0002);  // input 2: not the one armed
  r.run_ms(5);
  EXPECT_EQ(r.st().state, RobotState::moving);
  r.bridge.set_digital_inputs(0x0001);
  r.run_ms(1);
  const rb::i32 latched = r.st().latched_z_um;
  EXPECT_EQ(latched, r.st().z_um);  // latched in this cycle, still braking
  r.run_ms(20);
  EXPECT_EQ(r.st().result, Result::guard_fired);
  EXPECT_EQ(r.st().guard_fired, 0x0002);
  EXPECT_EQ(r.st().latched_z_um, latched);
}

TEST(RobotBridge, ApproachWithoutAGuardStopsAtMaxTravel) {
  Rig r;
  ASSERT_EQ(r.commit(approach(1, 0x0004, 10000, -3000)), ModbusException::none);  // 3 mm up
  r.run_ms(400);
  EXPECT_EQ(r.st().done_seq, 1);
  EXPECT_EQ(r.st().result, Result::max_travel);
  EXPECT_EQ(r.st().z_um, 403000);
}

TEST(RobotBridge, RetryWithTheTakenSeqIsNotRunAgain) {
  Rig r;
  ASSERT_EQ(r.commit(move_lin_rel(7, 1000, 10000)), ModbusException::none);
  r.run_ms(300);
  ASSERT_EQ(r.st().done_seq, 7);
  ASSERT_EQ(r.st().z_um, 399000);
  ASSERT_EQ(r.commit(move_lin_rel(7, 1000, 10000)), ModbusException::none);
  r.run_ms(300);
  EXPECT_EQ(r.st().z_um, 399000);
  EXPECT_EQ(r.st().state, RobotState::idle);
  EXPECT_EQ(r.bridge.counters().commands, 1u);
}

TEST(RobotBridge, SeqZeroNeverCommits) {
  Rig r;
  ASSERT_EQ(r.commit(move_lin_rel(0, 1000, 10000)), ModbusException::none);
  r.run_ms(10);
  EXPECT_EQ(r.st().ack_seq, 0);
  EXPECT_EQ(r.st().state, RobotState::idle);
}

TEST(RobotBridge, EveryRejectionCodeWithItsDetail) {
  Rig r;
  rb::Command c = move_lin_rel(1, 1000, 10000);
  c.code = static_cast<CommandCode>(99);
  r.commit(c);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_seq, 1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_unknown_command);

  r.commit(move_lin_rel(2, 1000, 0));  // speed 0
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_bad_parameter);
  EXPECT_EQ(r.st().reject_detail, 306);

  c = move_lin_rel(3, 1000, 10000);
  c.axis = Axis::tool_z;  // unused by move_lin_rel
  r.commit(c);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_bad_parameter);
  EXPECT_EQ(r.st().reject_detail, 303);

  r.commit(move_lin_rel(4, -1000000, 10000));  // 1 m up: outside the 0.8 m sphere
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_unreachable);
  EXPECT_EQ(r.st().reject_detail, 0);

  r.commit(move_lin_rel(5, 10000, 1000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::accepted);
  r.commit(move_lin_rel(6, 10000, 1000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_busy);
  rb::Command tool{};
  tool.seq = 7;
  tool.code = CommandCode::set_tool;
  tool.tool = 1;
  r.commit(tool);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_busy);
  EXPECT_EQ(r.st().done_seq, 0);  // rejections never move done_seq

  r.bridge.inject_fault();
  r.run_ms(20);
  EXPECT_EQ(r.st().done_seq, 5);
  EXPECT_EQ(r.st().result, Result::robot_fault);
  EXPECT_EQ(r.st().state, RobotState::faulted);
  r.commit(move_lin_rel(8, 1000, 1000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_faulted);
  rb::Command hold{};
  hold.seq = 9;
  hold.code = CommandCode::hold;
  r.commit(hold);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_faulted);
  rb::Command reset{};
  reset.seq = 10;
  reset.code = CommandCode::reset_fault;
  r.commit(reset);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::accepted);
  EXPECT_EQ(r.st().done_seq, 10);
  EXPECT_EQ(r.st().result, Result::done);
  EXPECT_EQ(r.st().state, RobotState::idle);

  r.bridge.reject_next(Result::rejected_not_ready, 1);
  r.commit(move_lin_rel(11, 1000, 1000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_not_ready);
  r.commit(move_lin_rel(12, 1000, 1000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::accepted);
}

TEST(RobotBridge, StaleHeartbeatStopsAMotionWithWatchdogAndRejectsMotionsUntilItChanges) {
  Rig r;
  ASSERT_EQ(r.commit(move_lin_rel(1, 50000, 10000)), ModbusException::none);  // 5 s
  r.run_ms(1000);
  r.keep_alive = false;
  r.heartbeat();
  r.run_ms(450);
  EXPECT_EQ(r.st().state, RobotState::moving);  // 500 ms since the last heartbeat: not yet
  r.run_ms(100);
  EXPECT_EQ(r.st().done_seq, 1);
  EXPECT_EQ(r.st().result, Result::watchdog);
  EXPECT_EQ(r.st().status_bits & rb::bit(StatusBit::watchdog_tripped), rb::bit(StatusBit::watchdog_tripped));
  EXPECT_EQ(r.st().status_bits & rb::bit(StatusBit::host_heartbeat_ok), 0);
  EXPECT_EQ(r.st().status_bits & rb::bit(StatusBit::latched_pose_valid), rb::bit(StatusBit::latched_pose_valid));
  r.commit(move_lin_rel(2, 1000, 10000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::rejected_heartbeat_stale);
  rb::Command hold{};
  hold.seq = 3;
  hold.code = CommandCode::hold;
  r.commit(hold);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::accepted);  // hold is accepted while stale
  EXPECT_EQ(r.st().status_bits & rb::bit(StatusBit::watchdog_tripped), 0);  // cleared by it
  r.heartbeat();
  r.commit(move_lin_rel(4, 1000, 10000));
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_result, Result::accepted);
}

TEST(RobotBridge, WatchdogCountsWallTimeNotVirtualTime) {
  Rig r;
  r.keep_alive = false;
  r.heartbeat();
  ASSERT_EQ(r.commit(move_lin_rel(1, 50000, 10000)), ModbusException::none);
  for (int k = 0; k < 2000; ++k) r.bridge.advance(1e-3, r.wall_us);  // 2 s virtual, no wall time
  EXPECT_EQ(r.st().state, RobotState::moving);
  r.wall_us += 600'000;
  r.bridge.advance(1e-3, r.wall_us);
  r.run_ms(60);
  EXPECT_EQ(r.st().result, Result::watchdog);
}

TEST(RobotBridge, ClosedConnectionStopsAMotionWithWatchdog) {
  Rig r;
  ASSERT_EQ(r.commit(move_lin_rel(1, 50000, 10000)), ModbusException::none);
  r.run_ms(100);
  r.bridge.connection_closed();
  r.run_ms(30);
  EXPECT_EQ(r.st().done_seq, 1);
  EXPECT_EQ(r.st().result, Result::watchdog);
  EXPECT_EQ(r.st().state, RobotState::idle);
}

TEST(RobotBridge, HoldSupersedesTheMotionThenFinishesDoneWhenStationary) {
  Rig r;
  ASSERT_EQ(r.commit(move_lin_rel(1, 50000, 10000)), ModbusException::none);
  r.run_ms(100);
  rb::Command hold{};
  hold.seq = 2;
  hold.code = CommandCode::hold;
  r.commit(hold);
  r.run_ms(1);
  EXPECT_EQ(r.st().done_seq, 1);
  EXPECT_EQ(r.st().result, Result::superseded);
  EXPECT_EQ(r.st().state, RobotState::moving);
  r.run_ms(20);
  EXPECT_EQ(r.st().done_seq, 2);
  EXPECT_EQ(r.st().result, Result::done);
  EXPECT_EQ(r.st().state, RobotState::idle);
}

TEST(RobotBridge, SetToolMovesTheReportedTcpAndSetsTheBit) {
  Rig r;
  rb::Command tool{};
  tool.seq = 1;
  tool.code = CommandCode::set_tool;
  tool.tool = 3;
  tool.z_um = 200000;
  r.commit(tool);
  r.run_ms(1);
  EXPECT_EQ(r.st().done_seq, 1);
  EXPECT_EQ(r.st().result, Result::done);
  EXPECT_EQ(r.st().tool, 3);
  EXPECT_EQ(r.st().z_um, 200000);  // the flange points down: the TCP is 200 mm lower
  EXPECT_NE(r.st().status_bits & rb::bit(StatusBit::tool_set), 0);
}

TEST(RobotBridge, ForceIsTheExternalForceAgainstTheApproachDirection) {
  Rig r;
  const double up[3] = {0, 0, 1.5};  // the specimen pushes the downward-pointing tool up
  r.bridge.set_external_force(up, true);
  r.bridge.advance(1e-3, r.wall_us);
  EXPECT_EQ(r.st().force_mN, 1500);
  EXPECT_NE(r.st().status_bits & rb::bit(StatusBit::force_valid), 0);
  r.bridge.set_external_force(up, false);
  r.bridge.advance(1e-3, r.wall_us);
  EXPECT_EQ(r.st().status_bits & rb::bit(StatusBit::force_valid), 0);
}

TEST(RobotBridge, HalfTurnAnglesAreReportedAsPlus180000WhateverTheRoundingNoise) {
  plant::RobotArm arm{plant::pose_from_xyzabc(0.5, 0.0, 0.4, -kPi, 0, -kPi + 1e-12)};
  RobotBridge bridge{arm};
  bridge.advance(1e-3, 0);
  EXPECT_EQ(bridge.status().a_mdeg, 180000);
  EXPECT_EQ(bridge.status().c_mdeg, 180000);
}

TEST(RobotBridge, AccessRulesAnswerTheSpecsExceptionCodes) {
  Rig r;
  rb::u16 buf[130]{};
  EXPECT_EQ(r.bridge.read(100, 53, buf), ModbusException::none);
  EXPECT_EQ(r.bridge.read(113, 6, buf), ModbusException::none);  // a part of one block
  EXPECT_EQ(r.bridge.read(95, 10, buf), ModbusException::illegal_data_address);   // across
  EXPECT_EQ(r.bridge.read(100, 54, buf), ModbusException::illegal_data_address);  // past the end
  EXPECT_EQ(r.bridge.read(500, 1, buf), ModbusException::illegal_data_address);
  EXPECT_EQ(r.bridge.read(100, 0, buf), ModbusException::illegal_data_value);
  EXPECT_EQ(r.bridge.read(0, 126, buf), ModbusException::illegal_data_value);
  const rb::u16 one[1] = {5};
  EXPECT_EQ(r.bridge.write(101, one, true), ModbusException::illegal_data_address);  // R block
  EXPECT_EQ(r.bridge.write(0, one, false), ModbusException::illegal_data_address);
  EXPECT_EQ(r.bridge.write(300, one, true), ModbusException::illegal_data_address);  // FC6 to cmd
  const rb::u16 part[10]{};
  EXPECT_EQ(r.bridge.write(300, part, false), ModbusException::illegal_data_address);
  EXPECT_EQ(r.bridge.write(302, std::span<const rb::u16>(buf, 24), false),
            ModbusException::illegal_data_address);
  EXPECT_EQ(r.bridge.write(201, std::span<const rb::u16>(buf, 3), false),
            ModbusException::illegal_data_address);  // control across into nothing
  const rb::u16 wd_low[1] = {99}, wd_high[1] = {10001}, wd_ok[1] = {1000};
  EXPECT_EQ(r.bridge.write(202, wd_low, true), ModbusException::illegal_data_value);
  EXPECT_EQ(r.bridge.write(202, wd_high, true), ModbusException::illegal_data_value);
  rb::u16 ctl[3];
  r.bridge.read(200, 3, ctl);
  EXPECT_EQ(ctl[2], 500);  // kept
  EXPECT_EQ(r.bridge.write(202, wd_ok, true), ModbusException::none);
  r.bridge.read(200, 3, ctl);
  EXPECT_EQ(ctl[2], 1000);
  const rb::u16 ctl3[3] = {1, 0, 300};
  EXPECT_EQ(r.bridge.write(200, ctl3, false), ModbusException::none);
  r.run_ms(1);
  EXPECT_EQ(r.bridge.control().watchdog_ms, 300);
}

TEST(RobotBridge, AWriteTakesEffectAtItsApplyTime) {
  Rig r;
  std::array<rb::u16, rb::Command::kLength> regs{};
  rb::encode(move_lin_rel(1, 1000, 10000), std::span<rb::u16, rb::Command::kLength>(regs));
  EXPECT_TRUE(r.bridge.is_reaction(300, regs));
  ASSERT_EQ(r.bridge.write(300, regs, false, r.bridge.time_s() + 0.005), ModbusException::none);
  EXPECT_FALSE(r.bridge.is_reaction(300, regs));  // the same seq again is no new command
  r.run_ms(4);
  EXPECT_EQ(r.st().ack_seq, 0);
  r.run_ms(1);
  EXPECT_EQ(r.st().ack_seq, 1);
}

}  // namespace
}  // namespace palp::sim
