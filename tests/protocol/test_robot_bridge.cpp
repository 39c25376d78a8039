// SPDX-License-Identifier: Apache-2.0
// The robot bridge's register map (protocol/robot-bridge.md, robot_bridge/*.hpp): the int32
// golden vectors, every block both ways, the typed decode errors, the command checks, and the
// spec's tables and hex examples against this build.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "palp/protocol/robot_bridge/check.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"
#include "source_file.hpp"

namespace palp::proto::rb {
namespace {

template <class B>
std::vector<u16> regs_of(const B& b) {
  std::vector<u16> r(B::kLength);
  encode(b, std::span<u16, B::kLength>(r.data(), B::kLength));
  return r;
}

std::string hex_words(const std::vector<u16>& r) {
  std::string s;
  char w[8];
  for (u16 v : r) {
    std::snprintf(w, sizeof w, "%s%04x", s.empty() ? "" : " ", v);
    s += w;
  }
  return s;
}

// ---- the examples: robot-bridge.md §10 quotes them ------------------------------------------
StatusBlock example_status() {  // a guarded approach that stopped on the force guard
  StatusBlock s;
  s.heartbeat = 4660;
  s.state = RobotState::idle;
  s.status_bits = bit(StatusBit::drives_enabled) | bit(StatusBit::automatic_mode) |
                  bit(StatusBit::host_heartbeat_ok) | bit(StatusBit::latched_pose_valid) |
                  bit(StatusBit::force_valid) | bit(StatusBit::tool_set);
  s.ack_seq = 42;
  s.ack_result = Result::accepted;
  s.done_seq = 42;
  s.result = Result::guard_fired;
  s.guard_fired = bit(GuardSource::force);
  s.stop_seen = 3;
  s.tool = 1;
  s.robot_time_ms = 123456789;
  s.x_um = 500000, s.y_um = -123456, s.z_um = 212345;
  s.a_mdeg = 180000, s.b_mdeg = 0, s.c_mdeg = -179999;
  s.latched_x_um = 500000, s.latched_y_um = -123456, s.latched_z_um = 212350;
  s.latched_a_mdeg = 180000, s.latched_b_mdeg = 0, s.latched_c_mdeg = -179999;
  s.force_mN = 2500;
  s.a1_mdeg = 0, s.a2_mdeg = 30000, s.a3_mdeg = 0, s.a4_mdeg = -90000;
  s.a5_mdeg = 0, s.a6_mdeg = 60000, s.a7_mdeg = -45000;
  return s;
}

Command example_approach() {  // down the tool's +z at 2 mm/s, at most 20 mm, until 2 N or a stop
  Command c;
  c.seq = 42;
  c.code = CommandCode::guarded_approach;
  c.guard_sources = bit(GuardSource::host_stop) | bit(GuardSource::force);
  c.axis = Axis::tool_z;
  c.speed = 2000;
  c.force_threshold_mN = 2000;
  c.max_travel_um = 20000;
  return c;
}

Command example_move_lin() {
  Command c;
  c.seq = 41;
  c.code = CommandCode::move_lin;
  c.speed = 50000;
  c.x_um = 500000, c.y_um = -123456, c.z_um = 200000;
  c.a_mdeg = 180000, c.b_mdeg = 0, c.c_mdeg = -179999;
  return c;
}

HostControl example_control() { return HostControl{7, 3, 500}; }

template <class F>
void for_each_example(F&& f) {
  f("Identification.this", this_identification());
  f("StatusBlock.after_guard", example_status());
  f("HostControl.example", example_control());
  f("Command.guarded_approach", example_approach());
  f("Command.move_lin", example_move_lin());
}

constexpr i32 kInt32Vectors[] = {0, 1, -1, INT32_MIN, INT32_MAX, 123456789, -123456789};

std::string vectors_text() {
  std::string t =
      "# palp robot bridge register map 1.0: golden vectors (protocol/robot-bridge.md section 10)\n"
      "# 'int32 <value> <high> <low>': a 32-bit value as two registers, high word first.\n"
      "# 'block <Block>.<label> <address>' then 'regs': the block's registers from <address>.\n"
      "# Registers are 16-bit words in hex. tests/protocol/test_robot_bridge.cpp checks this file.\n\n";
  char line[96];
  for (i32 v : kInt32Vectors) {
    u16 r[2];
    put_i32(v, r);
    std::snprintf(line, sizeof line, "int32 %ld %04x %04x\n", static_cast<long>(v), r[0], r[1]);
    t += line;
  }
  for_each_example([&](const char* label, const auto& b) {
    using B = std::decay_t<decltype(b)>;
    std::snprintf(line, sizeof line, "\nblock %s %u\n", label, B::kAddress);
    t += line;
    t += "regs " + hex_words(regs_of(b)) + "\n";
  });
  return t;
}

// The records of protocol/vectors/robot_bridge.txt.
struct Vectors {
  std::vector<std::pair<long, std::vector<u16>>> int32s;
  std::map<std::string, std::pair<unsigned, std::vector<u16>>> blocks;
};

std::vector<u16> parse_words(std::istream& in) {
  std::vector<u16> out;
  std::string w;
  while (in >> w) {
    EXPECT_EQ(w.size(), 4u) << w;
    out.push_back(static_cast<u16>(std::stoul(w, nullptr, 16)));
  }
  return out;
}

Vectors parse_vectors() {
  Vectors v;
  std::istringstream file(palp::test::read_source("protocol/vectors/robot_bridge.txt"));
  std::string line, block;
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "int32") {
      long value = 0;
      in >> value;
      v.int32s.emplace_back(value, parse_words(in));
    } else if (key == "block") {
      unsigned address = 0;
      in >> block >> address;
      v.blocks[block].first = address;
    } else if (key == "regs") {
      v.blocks[block].second = parse_words(in);
    } else {
      EXPECT_TRUE(key.empty() || key[0] == '#') << line;
    }
  }
  return v;
}

TEST(RobotBridgeVectors, FileIsWhatThisBuildGenerates) {
  if (std::getenv("PALP_RB_WRITE_VECTORS") != nullptr) {  // regenerate: see robot-bridge.md §11
    std::ofstream(std::string(PALP_SOURCE_DIR) + "/protocol/vectors/robot_bridge.txt", std::ios::binary)
        << vectors_text();
  }
  EXPECT_EQ(palp::test::read_source("protocol/vectors/robot_bridge.txt"), vectors_text())
      << "the map or the codec changed: if intended, bump the map version and rerun with "
         "PALP_RB_WRITE_VECTORS=1 set";
}

TEST(RobotBridgeVectors, Int32EncodesHighWordFirstAndDecodesBack) {
  const Vectors v = parse_vectors();
  ASSERT_EQ(v.int32s.size(), std::size(kInt32Vectors));
  for (const auto& [value, regs] : v.int32s) {
    ASSERT_EQ(regs.size(), 2u);
    u16 r[2];
    put_i32(static_cast<i32>(value), r);
    EXPECT_EQ(r[0], regs[0]) << value;
    EXPECT_EQ(r[1], regs[1]) << value;
    EXPECT_EQ(get_i32(regs.data()), value);
  }
  u16 r[2];
  put_i32(-1, r);
  EXPECT_EQ(r[0], 0xFFFF);
  EXPECT_EQ(r[1], 0xFFFF);
  put_i32(123456789, r);  // 0x075BCD15
  EXPECT_EQ(r[0], 0x075B);
  EXPECT_EQ(r[1], 0xCD15);
  put_i32(INT32_MIN, r);
  EXPECT_EQ(r[0], 0x8000);
  EXPECT_EQ(r[1], 0x0000);
}

TEST(RobotBridgeVectors, EveryBlockExampleEncodesToItsRegistersAndDecodesBack) {
  const Vectors v = parse_vectors();
  int n = 0;
  for_each_example([&](const char* label, const auto& example) {
    using B = std::decay_t<decltype(example)>;
    ++n;
    const auto it = v.blocks.find(label);
    ASSERT_NE(it, v.blocks.end()) << label;
    EXPECT_EQ(it->second.first, B::kAddress) << label;
    EXPECT_EQ(hex_words(regs_of(example)), hex_words(it->second.second)) << label;
    B decoded;
    EXPECT_TRUE(decode(std::span<const u16>(it->second.second), decoded).ok()) << label;
    EXPECT_EQ(decoded, example) << label;
  });
  EXPECT_EQ(static_cast<std::size_t>(n), v.blocks.size());
}

// ---- round trips and errors -----------------------------------------------------------------
template <class B>
B filled(u32 seed) {  // every register non-zero, 32-bit values of both signs, enums valid
  B b;
  B::visit(b, [&](auto& v) {
    using T = std::decay_t<decltype(v)>;
    seed = seed * 1664525u + 1013904223u;
    if constexpr (std::is_enum_v<T>) {
      const auto& values = EnumInfo<T>::values;
      v = static_cast<T>(values[seed % std::size(values)].value);
    } else {
      v = static_cast<T>(seed);
    }
  });
  return b;
}

TEST(RobotBridgeCodec, EveryBlockRoundTripsThroughItsRegisters) {
  for_each_block([](auto empty) {
    using B = decltype(empty);
    for (u32 seed = 1; seed < 200; ++seed) {
      B b = filled<B>(seed);
      if constexpr (std::is_same_v<B, Identification>) b.magic = kMagic, b.map_major = kMapMajor;
      const std::vector<u16> r = regs_of(b);
      B back;
      ASSERT_TRUE(decode(std::span<const u16>(r), back).ok()) << B::kName;
      EXPECT_EQ(back, b) << B::kName;
    }
  });
}

TEST(RobotBridgeCodec, BlocksFitOneModbusRequestAndDoNotOverlap) {
  u16 next = 0;
  for_each_block([&](auto b) {
    using B = decltype(b);
    EXPECT_GE(B::kAddress, next) << B::kName;
    next = static_cast<u16>(B::kAddress + B::kLength);
    EXPECT_LE(B::kLength, kMaxReadRegisters) << B::kName;
    if (std::string(B::kAccess) == "RW") {
      EXPECT_LE(B::kLength, kMaxWriteRegisters) << B::kName;
    }
  });
  EXPECT_EQ(kDefaultPort, 30005);
}

TEST(RobotBridgeCodec, BadEnumNamesItsRegister) {
  std::vector<u16> r = regs_of(example_status());
  r[1] = 99;  // state
  StatusBlock s;
  EXPECT_EQ(decode(std::span<const u16>(r), s), (DecodeResult{DecodeError::bad_enum, 101}));
  r = regs_of(example_status());
  r[7] = 10;  // result: 10 is not a Result
  EXPECT_EQ(decode(std::span<const u16>(r), s), (DecodeResult{DecodeError::bad_enum, 107}));
  r = regs_of(example_approach());
  r[3] = 7;  // axis
  Command c;
  EXPECT_EQ(decode(std::span<const u16>(r), c), (DecodeResult{DecodeError::bad_enum, 303}));
}

TEST(RobotBridgeCodec, IdentificationChecksMagicAndMajorButAcceptsANewerMinor) {
  Identification id;
  std::vector<u16> r = regs_of(this_identification());
  EXPECT_EQ(r[0], 0x5041);  // "PA"
  EXPECT_EQ(r[1], 0x4C50);  // "LP"
  r[1] = 0x4C51;
  EXPECT_EQ(decode(std::span<const u16>(r), id), (DecodeResult{DecodeError::bad_magic, 0}));
  r = regs_of(this_identification());
  r[2] = 2;
  EXPECT_EQ(decode(std::span<const u16>(r), id), (DecodeResult{DecodeError::incompatible_version, 2}));
  r = regs_of(this_identification());
  r[3] = 7;
  EXPECT_TRUE(decode(std::span<const u16>(r), id).ok());
  EXPECT_EQ(id.map_minor, 7);
}

TEST(RobotBridgeCodec, WrongLengthIsRefused) {
  std::vector<u16> r = regs_of(example_control());
  r.push_back(0);
  HostControl h;
  EXPECT_EQ(decode(std::span<const u16>(r), h).error, DecodeError::wrong_length);
}

// ---- command checks -------------------------------------------------------------------------
TEST(RobotBridgeCheck, TheExamplesAreAccepted) {
  EXPECT_TRUE(check_command(example_approach()).accepted());
  EXPECT_TRUE(check_command(example_move_lin()).accepted());
  Command hold;
  hold.seq = 1, hold.code = CommandCode::hold;
  EXPECT_TRUE(check_command(hold).accepted());
}

TEST(RobotBridgeCheck, BadParametersNameTheirRegister) {
  Command c = example_approach();
  c.guard_sources = 0;
  EXPECT_EQ(check_command(c), (CommandVerdict{Result::rejected_bad_parameter, 302}));
  c = example_approach();
  c.max_travel_um = 0;
  EXPECT_EQ(check_command(c), (CommandVerdict{Result::rejected_bad_parameter, 310}));
  c = example_approach();
  c.guard_sources |= bit(GuardSource::digital_input);  // no input named
  EXPECT_EQ(check_command(c), (CommandVerdict{Result::rejected_bad_parameter, 304}));
  c = example_move_lin();
  c.max_travel_um = 5;  // unused by move_lin: must be zero
  EXPECT_EQ(check_command(c), (CommandVerdict{Result::rejected_bad_parameter, 310}));
  c = example_move_lin();
  c.speed = 0;
  EXPECT_EQ(check_command(c), (CommandVerdict{Result::rejected_bad_parameter, 306}));
}

TEST(RobotBridgeCheck, UnknownCodeAndBadEnumsFromRawRegisters) {
  std::vector<u16> r = regs_of(example_approach());
  Command c;
  r[1] = 99;
  EXPECT_EQ(check_command(std::span<const u16>(r), c), (CommandVerdict{Result::rejected_unknown_command, 0}));
  r[1] = 0;  // none
  EXPECT_EQ(check_command(std::span<const u16>(r), c), (CommandVerdict{Result::rejected_unknown_command, 0}));
  r = regs_of(example_approach());
  r[3] = 50;
  EXPECT_EQ(check_command(std::span<const u16>(r), c), (CommandVerdict{Result::rejected_bad_parameter, 303}));
}

}  // namespace
}  // namespace palp::proto::rb
