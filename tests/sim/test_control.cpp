// SPDX-License-Identifier: Apache-2.0
// palp-sim's control channel: every command parses to its values; every bad line is refused with
// a reason naming the command and the word.
#include <gtest/gtest.h>

#include "palp/sim/control.hpp"

namespace palp::sim {
namespace {

template <class T>
T parse_as(const char* line) {
  std::string error;
  const auto c = parse_control(line, error);
  EXPECT_TRUE(c.has_value()) << line << ": " << error;
  EXPECT_TRUE(c && std::holds_alternative<T>(*c)) << line;
  return c && std::holds_alternative<T>(*c) ? std::get<T>(*c) : T{};
}

std::string error_of(const char* line) {
  std::string error;
  EXPECT_FALSE(parse_control(line, error).has_value()) << line;
  return error;
}

TEST(Control, MountTakesThreeCoordinatesInMillimetres) {
  const cmd::Mount m = parse_as<cmd::Mount>("mount 12.5 -3 40");
  EXPECT_DOUBLE_EQ(m.x_mm, 12.5);
  EXPECT_DOUBLE_EQ(m.y_mm, -3.0);
  EXPECT_DOUBLE_EQ(m.z_mm, 40.0);
}

TEST(Control, PaceUnderstandsRealtimeFastAndFactors) {
  EXPECT_DOUBLE_EQ(parse_as<cmd::Pace>("pace realtime").factor, 1.0);
  EXPECT_DOUBLE_EQ(parse_as<cmd::Pace>("pace fast").factor, 0.0);
  EXPECT_DOUBLE_EQ(parse_as<cmd::Pace>("  pace   50 ").factor, 50.0);
}

TEST(Control, AnnounceTakesAVersionAndAnOptionalHash) {
  const cmd::Announce a = parse_as<cmd::Announce>("announce 1.2 0xDEADbeef");
  EXPECT_FALSE(a.actual);
  EXPECT_EQ(a.major, 1);
  EXPECT_EQ(a.minor, 2);
  ASSERT_TRUE(a.hash.has_value());
  EXPECT_EQ(*a.hash, 0xDEADBEEFu);
  EXPECT_FALSE(parse_as<cmd::Announce>("announce 0.9").hash.has_value());
  EXPECT_TRUE(parse_as<cmd::Announce>("announce actual").actual);
}

TEST(Control, FaultKnobsAndTimesParse) {
  EXPECT_EQ(parse_as<cmd::DropFrames>("drop-frames 100").every, 100u);
  EXPECT_EQ(parse_as<cmd::CorruptFrames>("corrupt-frames 0").every, 0u);
  EXPECT_EQ(parse_as<cmd::Seed>("seed 18446744073709551615").seed, 18446744073709551615ull);
  EXPECT_DOUBLE_EQ(parse_as<cmd::ReactionLatency>("reaction-latency 2.5").ms, 2.5);
  EXPECT_DOUBLE_EQ(parse_as<cmd::HoldTimeout>("hold-timeout 1000").ms, 1000.0);
  EXPECT_EQ(parse_as<cmd::Phantom>("phantom solid_1d").name, "solid_1d");
}

TEST(Control, BadLinesAreRefusedWithTheCommandAndTheWord) {
  EXPECT_EQ(error_of(""), "empty command; try 'help'");
  EXPECT_EQ(error_of("fly away"), "unknown command 'fly'; try 'help'");
  EXPECT_EQ(error_of("mount 1 2"), "mount: expected <x_mm> <y_mm> <z_mm>");
  EXPECT_EQ(error_of("mount 1 2 3mm"), "mount: '3mm' is not a number of mm");
  EXPECT_EQ(error_of("mount 1 nan 3"), "mount: 'nan' is not a number of mm");
  EXPECT_EQ(error_of("pace -2"), "pace: '-2' is not realtime, fast or a factor > 0");
  EXPECT_EQ(error_of("seed -1"), "seed: '-1' is not an unsigned integer");
  EXPECT_EQ(error_of("announce 1"), "announce: '1' is not a version <major>.<minor> (0-255 each)");
  EXPECT_EQ(error_of("announce 1.300"),
            "announce: '1.300' is not a version <major>.<minor> (0-255 each)");
  EXPECT_EQ(error_of("announce 1.2 dead"), "announce: 'dead' is not a schema hash 0x<hex, 32 bits>");
  EXPECT_EQ(error_of("phantom ../etc/passwd"),
            "phantom: '../etc/passwd' is not a phantom name (letters, digits, _ and -)");
  EXPECT_EQ(error_of("hold-timeout -5"), "hold-timeout: '-5' is not a duration in ms >= 0");
  EXPECT_EQ(error_of("status now"), "status: expected no arguments");
}

TEST(Control, RobotKnobsParseToTheirValues) {
  EXPECT_DOUBLE_EQ(parse_as<cmd::RobotReplyDelay>("robot-reply-delay 750").ms, 750.0);
  parse_as<cmd::RobotDrop>("robot-drop");
  parse_as<cmd::RobotFault>("robot-fault");
  EXPECT_TRUE(parse_as<cmd::RobotFreezeHeartbeat>("robot-freeze-heartbeat on").on);
  EXPECT_FALSE(parse_as<cmd::RobotFreezeHeartbeat>("robot-freeze-heartbeat off").on);
  const cmd::RobotReject r = parse_as<cmd::RobotReject>("robot-reject rejected_not_ready 3");
  EXPECT_EQ(r.result, 35);
  EXPECT_EQ(r.count, 3u);
}

TEST(Control, BadRobotKnobsAreRefusedNamingTheWord) {
  EXPECT_EQ(error_of("robot-reply-delay -1"), "robot-reply-delay: '-1' is not a duration in ms >= 0");
  EXPECT_EQ(error_of("robot-freeze-heartbeat maybe"), "robot-freeze-heartbeat: 'maybe' is not on or off");
  EXPECT_EQ(error_of("robot-reject done 1"),
            "robot-reject: 'done' is not a rejection result (rejected_busy, rejected_not_ready, ...)");
  EXPECT_EQ(error_of("robot-reject rejected_busy x"), "robot-reject: 'x' is not an unsigned integer");
  EXPECT_EQ(error_of("robot-drop now"), "robot-drop: expected no arguments");
}

TEST(Control, HelpListsTheRobotKnobs) {
  const std::string help = control_help();
  for (const char* k : {"robot-reply-delay", "robot-drop", "robot-freeze-heartbeat", "robot-reject",
                        "robot-fault"})
    EXPECT_NE(help.find(k), std::string::npos) << k;
}

}  // namespace
}  // namespace palp::sim
