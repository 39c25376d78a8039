// SPDX-License-Identifier: Apache-2.0
// The robot client's conversions, without a bridge: SI arguments to command registers (exact
// registers against robot-bridge.md §10, rounding to nearest, the map's limits refused locally
// with the register named), the status block in SI, the identification checks, and the texts of
// rejections and faults.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "palp/error.hpp"
#include "robot/robot_convert.hpp"

namespace {

namespace rb = palp::proto::rb;
using palp::GuardedApproach;
using palp::Pose;
using namespace palp::detail;
using testing::HasSubstr;

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

std::array<std::uint16_t, rb::Command::kLength> registers(const rb::Command& c) {
  std::array<std::uint16_t, rb::Command::kLength> r{};
  rb::encode(c, std::span<std::uint16_t, rb::Command::kLength>(r));
  return r;
}

std::string config_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "no error";
}

std::string check_error(const rb::Command& c) {
  return config_error([&] { check_command_or_throw(c); });
}

}  // namespace

TEST(RobotConvert, MoveLinInSiGivesTheRegistersOfTheSpecExample10_4) {
  const Pose target{0.5, -0.123456, 0.2, 180.0 * kRadPerDeg, 0.0, -179.999 * kRadPerDeg};
  rb::Command c = motion_command(rb::CommandCode::move_lin, target, 0.05);
  c.seq = 41;
  const std::array<std::uint16_t, 24> expected = {
      0x0029, 0x0001, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0xc350,
      0x0000, 0x0000, 0x0000, 0x0000, 0x0007, 0xa120, 0xfffe, 0x1dc0,
      0x0003, 0x0d40, 0x0002, 0xbf20, 0x0000, 0x0000, 0xfffd, 0x40e1};
  EXPECT_EQ(registers(c), expected);
  EXPECT_NO_THROW(check_command_or_throw(c));
}

TEST(RobotConvert, GuardedApproachInSiGivesTheRegistersOfTheSpecExample10_3) {
  GuardedApproach g;
  g.axis = rb::Axis::tool_z;
  g.speed_m_per_s = 2e-3;
  g.max_travel_m = 20e-3;
  g.guard_host_stop = true;
  g.force_threshold_N = 2.0;
  rb::Command c = approach_command(g);
  c.seq = 42;
  const std::array<std::uint16_t, 24> expected = {
      0x002a, 0x0004, 0x0005, 0x0003, 0x0000, 0x0000, 0x0000, 0x07d0,
      0x0000, 0x07d0, 0x0000, 0x4e20, 0x0000, 0x0000, 0x0000, 0x0000,
      0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000};
  EXPECT_EQ(registers(c), expected);
}

TEST(RobotConvert, DigitalInputGuardSetsItsBitAndInputAndNegativeTravelKeepsItsSign) {
  GuardedApproach g;
  g.guard_host_stop = false;
  g.digital_input = 1;
  g.max_travel_m = -5e-3;
  const rb::Command c = approach_command(g);
  EXPECT_EQ(c.guard_sources, rb::bit(rb::GuardSource::digital_input));
  EXPECT_EQ(c.digital_input, 1);
  EXPECT_EQ(c.max_travel_um, -5000);
  EXPECT_EQ(c.speed, 1000);
  EXPECT_EQ(c.force_threshold_mN, 0);
  EXPECT_NO_THROW(check_command_or_throw(c));
}

TEST(RobotConvert, SiValuesRoundToTheNearestRegisterUnitHalfAwayFromZero) {
  const Pose p{1.2345678e-3, -1.2345678e-3, 0.4e-6, 0.0015 * kRadPerDeg, -0.0015 * kRadPerDeg,
               0.0004 * kRadPerDeg};
  const rb::Command c = motion_command(rb::CommandCode::move_lin_rel, p, 0.0123456789);
  EXPECT_EQ(c.x_um, 1235);
  EXPECT_EQ(c.y_um, -1235);
  EXPECT_EQ(c.z_um, 0);
  EXPECT_EQ(c.a_mdeg, 2);
  EXPECT_EQ(c.b_mdeg, -2);
  EXPECT_EQ(c.c_mdeg, 0);
  EXPECT_EQ(c.speed, 12346);
  EXPECT_EQ(motion_command(rb::CommandCode::move_ptp, p, 0.25).speed, 250);  // permille
  GuardedApproach g;
  g.force_threshold_N = 1.0005;
  EXPECT_EQ(approach_command(g).force_threshold_mN, 1001);
}

TEST(RobotConvert, SetToolPutsIdAndFlangeFrameInTheirRegisters) {
  const rb::Command c = tool_command(3, Pose{0.0, 0.0, 0.2, 0.0, 0.0, 0.0});
  EXPECT_EQ(c.code, rb::CommandCode::set_tool);
  EXPECT_EQ(c.tool, 3);
  EXPECT_EQ(c.z_um, 200000);
  EXPECT_EQ(c.speed, 0);
  EXPECT_NO_THROW(check_command_or_throw(c));
}

TEST(RobotConvert, LimitsOfTheMapAreRefusedLocallyNamingTheRegister) {
  EXPECT_EQ(check_error(motion_command(rb::CommandCode::move_lin, Pose{}, 1.0000006)),
            "move_lin: register speed (306) would hold 1000001 um/s, out of range or not allowed "
            "for move_lin (robot-bridge.md §6); nothing was sent");
  EXPECT_NO_THROW(check_command_or_throw(motion_command(rb::CommandCode::move_lin, Pose{}, 1.0)));
  EXPECT_EQ(check_error(motion_command(rb::CommandCode::move_lin, Pose{}, 0.0000004)),
            "move_lin: register speed (306) would hold 0 um/s, out of range or not allowed for "
            "move_lin (robot-bridge.md §6); nothing was sent");
  EXPECT_THAT(check_error(motion_command(rb::CommandCode::move_ptp, Pose{}, 1.001)),
              HasSubstr("register speed (306) would hold 1001"));
  EXPECT_THAT(check_error(motion_command(rb::CommandCode::move_lin,
                                         Pose{0, 0, 0, 180.001 * kRadPerDeg, 0, 0}, 0.01)),
              HasSubstr("register a_mdeg (318) would hold 180001 mdeg"));
  EXPECT_NO_THROW(check_command_or_throw(
      motion_command(rb::CommandCode::move_lin, Pose{0, 0, 0, 0, 0, -std::numbers::pi}, 0.01)));

  GuardedApproach g;
  g.speed_m_per_s = 0.1000006;
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register speed (306) would hold 100001 um/s"));
  g = GuardedApproach{};
  g.max_travel_m = 0.0;
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register max_travel_um (310) would hold 0 um"));
  g.max_travel_m = -0.5000006;
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register max_travel_um (310) would hold -500001 um"));
  g = GuardedApproach{};
  g.digital_input = 17;
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register digital_input (304) would hold 17,"));
  g = GuardedApproach{};
  g.force_threshold_N = 0.0;
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register force_threshold_mN (308) would hold 0 mN"));
  g = GuardedApproach{};
  g.axis = rb::Axis::none;
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register axis (303) would hold 0,"));
  g = GuardedApproach{};
  g.guard_host_stop = false;  // no guard at all
  EXPECT_THAT(check_error(approach_command(g)), HasSubstr("register guard_sources (302) would hold 0,"));

  EXPECT_THAT(check_error(tool_command(0, Pose{})), HasSubstr("set_tool: register tool (305) would hold 0,"));
  EXPECT_THAT(check_error(tool_command(16, Pose{})), HasSubstr("register tool (305) would hold 16,"));
}

TEST(RobotConvert, ValuesBeyondInt32OrNotFiniteAreRefusedNamingTheRegister) {
  EXPECT_EQ(config_error([] { motion_command(rb::CommandCode::move_lin, Pose{3000.0, 0, 0, 0, 0, 0}, 0.01); }),
            "move_lin: 3000.000000 does not fit register x_um (312, int32 in um); nothing was sent");
  EXPECT_THAT(config_error([] { motion_command(rb::CommandCode::move_lin, Pose{0, NAN, 0, 0, 0, 0}, 0.01); }),
              HasSubstr("does not fit register y_um (314, int32 in um)"));
  EXPECT_THAT(config_error([] { motion_command(rb::CommandCode::move_lin, Pose{}, INFINITY); }),
              HasSubstr("does not fit register speed (306, int32 in um/s)"));
}

TEST(RobotConvert, RejectionsReadAsTheirResultNameAndMeaning) {
  EXPECT_EQ(rejection_text(rb::CommandCode::move_lin, 7, rb::Result::rejected_unreachable, 0),
            "robot bridge rejected move_lin (seq 7): rejected_unreachable — the target is outside "
            "the workspace or joint limits");
  EXPECT_EQ(rejection_text(rb::CommandCode::guarded_approach, 9, rb::Result::rejected_bad_parameter, 306),
            "robot bridge rejected guarded_approach (seq 9): rejected_bad_parameter — register "
            "speed (306) is out of range or not zero when unused");
  EXPECT_EQ(rejection_text(rb::CommandCode::move_ptp, 1, rb::Result::rejected_busy, 0),
            "robot bridge rejected move_ptp (seq 1): rejected_busy — a motion is in progress (send "
            "hold or a stop first)");
  EXPECT_EQ(rejection_text(rb::CommandCode::move_lin, 2, rb::Result::rejected_heartbeat_stale, 0),
            "robot bridge rejected move_lin (seq 2): rejected_heartbeat_stale — a motion was asked "
            "for while the host heartbeat is stale");
  EXPECT_EQ(rejection_text(rb::CommandCode::hold, 3, static_cast<rb::Result>(45), 0),
            "robot bridge rejected hold (seq 3): #45 — a value this SDK (register map 1.0) does not know");
}

TEST(RobotConvert, FaultsReadAsTheirResultNameAndMeaning) {
  EXPECT_EQ(fault_text(rb::CommandCode::move_lin, 7, rb::Result::robot_fault),
            "robot bridge: move_lin (seq 7) ended with robot_fault — a robot error ended the "
            "motion; state is faulted");
  EXPECT_EQ(fault_text(rb::CommandCode::guarded_approach, 8, rb::Result::safety_stopped),
            "robot bridge: guarded_approach (seq 8) ended with safety_stopped — the safety "
            "controller ended the motion");
  EXPECT_EQ(fault_text(rb::CommandCode::move_lin_rel, 9, rb::Result::watchdog),
            "robot bridge: move_lin_rel (seq 9) ended with watchdog — the host heartbeat went stale "
            "during the motion; the arm was stopped");
}

TEST(RobotConvert, StatusOfTheSpecExample10_2InSi) {
  const std::array<std::uint16_t, 53> regs = {
      0x1234, 0x0001, 0x0077, 0x002a, 0x0009, 0x0000, 0x002a, 0x0002,
      0x0004, 0x0003, 0x0001, 0x075b, 0xcd15, 0x0007, 0xa120, 0xfffe,
      0x1dc0, 0x0003, 0x3d79, 0x0002, 0xbf20, 0x0000, 0x0000, 0xfffd,
      0x40e1, 0x0007, 0xa120, 0xfffe, 0x1dc0, 0x0003, 0x3d7e, 0x0002,
      0xbf20, 0x0000, 0x0000, 0xfffd, 0x40e1, 0x0000, 0x09c4, 0x0000,
      0x0000, 0x0000, 0x7530, 0x0000, 0x0000, 0xfffe, 0xa070, 0x0000,
      0x0000, 0x0000, 0xea60, 0xffff, 0x5038};
  const palp::RobotStatus s = status_from_block(decode_status(regs, "modbus://h:1"));
  EXPECT_EQ(s.heartbeat, 4660);
  EXPECT_EQ(s.state, rb::RobotState::idle);
  EXPECT_EQ(s.ack_seq, 42);
  EXPECT_EQ(s.ack_result, rb::Result::accepted);
  EXPECT_EQ(s.done_seq, 42);
  EXPECT_EQ(s.result, rb::Result::guard_fired);
  EXPECT_EQ(s.guard_fired, rb::bit(rb::GuardSource::force));
  EXPECT_EQ(s.stop_seen, 3);
  EXPECT_EQ(s.tool, 1);
  EXPECT_DOUBLE_EQ(s.robot_time_s, 123456.789);
  EXPECT_DOUBLE_EQ(s.pose.x_m, 0.5);
  EXPECT_DOUBLE_EQ(s.pose.y_m, -0.123456);
  EXPECT_DOUBLE_EQ(s.pose.z_m, 0.212345);
  EXPECT_DOUBLE_EQ(s.pose.a_rad, std::numbers::pi);
  EXPECT_NEAR(s.pose.c_rad, -179.999 * kRadPerDeg, 1e-15);
  ASSERT_TRUE(s.latched.has_value());
  EXPECT_DOUBLE_EQ(s.latched->z_m, 0.21235);
  ASSERT_TRUE(s.force_N.has_value());
  EXPECT_DOUBLE_EQ(*s.force_N, 2.5);
  EXPECT_DOUBLE_EQ(s.joints_rad[1], 30.0 * kRadPerDeg);
  EXPECT_DOUBLE_EQ(s.joints_rad[3], -90.0 * kRadPerDeg);
  EXPECT_DOUBLE_EQ(s.joints_rad[6], -45.0 * kRadPerDeg);
}

TEST(RobotConvert, LatchedPoseAndForceAreAbsentWhenTheirBitsAreClear) {
  rb::StatusBlock b;
  b.latched_z_um = 1234;
  b.force_mN = 99;
  b.status_bits = rb::bit(rb::StatusBit::drives_enabled);
  const palp::RobotStatus s = status_from_block(b);
  EXPECT_FALSE(s.latched.has_value());
  EXPECT_FALSE(s.force_N.has_value());
}

TEST(RobotConvert, AStatusEnumValueThisSdkDoesNotKnowIsReportedByNumber) {
  std::array<std::uint16_t, 53> regs{};
  regs[107 - 100] = 45;
  try {
    decode_status(regs, "modbus://h:1");
    FAIL() << "decoded";
  } catch (const palp::ProtocolError& e) {
    EXPECT_EQ(std::string(e.what()), "robot bridge modbus://h:1: status register result (107) "
                                     "holds 45, a value this SDK (register map 1.0) does not know");
  }
}

namespace {
std::array<std::uint16_t, 10> identification_1_0() {
  return {0x5041, 0x4c50, 0x0001, 0x0000, 0x0064, 0x0035, 0x00c8, 0x0003, 0x012c, 0x0018};
}
template <class E>
std::string id_error(const std::array<std::uint16_t, 10>& regs) {
  try {
    check_identification(regs, "modbus://10.0.0.2:30005");
  } catch (const E& e) {
    return e.what();
  }
  return "accepted";
}
}  // namespace

TEST(RobotConvert, IdentificationOfA1_0BridgeIsAccepted) {
  const rb::Identification id = check_identification(identification_1_0(), "modbus://h:1");
  EXPECT_EQ(id.map_major, 1);
  EXPECT_EQ(id.status_length, 53);
}

TEST(RobotConvert, AnotherMagicIsNotAPalpBridge) {
  auto regs = identification_1_0();
  regs[0] = 0x1234;
  regs[1] = 0xabcd;
  EXPECT_EQ(id_error<palp::VersionError>(regs),
            "modbus://10.0.0.2:30005: not a palp robot bridge (magic 0x1234ABCD, expected "
            "0x50414C50 'PALP')");
}

TEST(RobotConvert, AnotherMajorNamesBothVersionsAndWhatToDo) {
  auto regs = identification_1_0();
  regs[2] = 2;
  regs[3] = 3;
  EXPECT_EQ(id_error<palp::VersionError>(regs),
            "robot bridge modbus://10.0.0.2:30005 serves register map 2.3 and this SDK speaks map "
            "1.0: another major version is incompatible; install the bridge application for map "
            "1.x on the robot, or use an SDK built for map 2.x");
}

TEST(RobotConvert, ANewerMinorWithLongerBlocksIsCompatible) {
  auto regs = identification_1_0();
  regs[3] = 4;
  regs[5] = 60;
  EXPECT_EQ(id_error<palp::Error>(regs), "accepted");
}

TEST(RobotConvert, BlocksShorterThanThisSdksOrElsewhereAreRefused) {
  auto regs = identification_1_0();
  regs[5] = 40;
  EXPECT_THAT(id_error<palp::ProtocolError>(regs), HasSubstr("status 100/40, control 200/3, command 300/24"));
  regs = identification_1_0();
  regs[8] = 400;
  EXPECT_THAT(id_error<palp::ProtocolError>(regs), HasSubstr("command 400/24 that this SDK (map 1.0) cannot use"));
}
