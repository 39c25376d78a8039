// SPDX-License-Identifier: Apache-2.0
// protocol/robot-bridge.md against this build: its register and enumeration tables are the
// map's (map.hpp), its hex register examples are golden vectors, its version is this build's.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "palp/protocol/robot_bridge/check.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"
#include "source_file.hpp"

namespace palp::proto::rb {
namespace {

const std::string& spec() {
  static const std::string text = palp::test::read_source("protocol/robot-bridge.md");
  return text;
}

/// The markdown table of a block's registers, as robot-bridge.md §5 must quote it.
template <class B>
std::string register_table() {
  std::string t = "| address | register | type | unit | meaning |\n|---|---|---|---|---|\n";
  unsigned at = B::kAddress;
  char addr[32];
  for (const RegisterInfo& r : B::kRegisters) {
    if (r.count == 1) std::snprintf(addr, sizeof addr, "%u", at);
    else std::snprintf(addr, sizeof addr, "%u-%u", at, at + r.count - 1);
    t += "| " + std::string(addr) + " | `" + r.name + "` | " + type_name(r) + " | " + r.unit + " | " +
         r.doc + " |\n";
    at += r.count;
  }
  return t;
}

/// The markdown table of an enumeration, as robot-bridge.md §7 must quote it.
template <class E>
std::string enum_table() {
  const std::string name = EnumInfo<E>::name;
  const bool bits = name == "StatusBit" || name == "GuardSource";
  std::string t = bits ? "| bit | mask | name | meaning |\n|---|---|---|---|\n"
                       : "| value | name | meaning |\n|---|---|---|\n";
  char head[48];
  for (const EnumValueInfo& v : EnumInfo<E>::values) {
    if (bits) std::snprintf(head, sizeof head, "| %u | 0x%04x |", v.value, 1u << v.value);
    else std::snprintf(head, sizeof head, "| %u |", v.value);
    t += std::string(head) + " `" + v.name + "` | " + v.doc + " |\n";
  }
  return t;
}

TEST(RobotBridgeSpec, QuotesEveryBlocksRegisterTable) {
  for_each_block([](auto b) {
    using B = decltype(b);
    const std::string table = register_table<B>();
    EXPECT_NE(spec().find(table), std::string::npos)
        << "robot-bridge.md lacks the register table of " << B::kName << " as map.hpp defines it:\n"
        << table;
  });
}

TEST(RobotBridgeSpec, QuotesEveryEnumerationTable) {
  for_each_enum([](auto info) {
    using Info = decltype(info);
    std::string table;
#define PALP_RB_X_TABLE(Name, doc) \
  if (std::string(Info::name) == #Name) table = enum_table<Name>();
    PALP_RB_ENUMS(PALP_RB_X_TABLE)
#undef PALP_RB_X_TABLE
    EXPECT_NE(spec().find("#### " + std::string(Info::name) + "\n\n" + Info::doc + "\n\n" + table),
              std::string::npos)
        << "robot-bridge.md lacks the table of " << Info::name << ":\n#### " << Info::name << "\n\n"
        << Info::doc << "\n\n" << table;
  });
}

TEST(RobotBridgeSpec, NamesThisBuildsMapVersionPortAndBlockAddresses) {
  char expected[96];
  std::snprintf(expected, sizeof expected, "This document describes **register map %u.%u**", kMapMajor,
                kMapMinor);
  EXPECT_NE(spec().find(expected), std::string::npos) << expected;
  EXPECT_NE(spec().find("TCP port **30005**"), std::string::npos);
  for_each_block([](auto b) {
    using B = decltype(b);
    char row[96];
    std::snprintf(row, sizeof row, "| %s | %u | %u | %s |", B::kName, B::kAddress, B::kLength, B::kAccess);
    EXPECT_NE(spec().find(row), std::string::npos) << row;
  });
}

// A fenced example is lines "<address>: <word> <word> ...", words as 4 hex digits. Every one
// must be (the start of) a golden vector's block at the same address.
TEST(RobotBridgeSpec, EveryHexRegisterExampleIsAGoldenVector) {
  std::string vectors;  // "<address>: <words>" of each block vector
  {
    std::istringstream in(palp::test::read_source("protocol/vectors/robot_bridge.txt"));
    std::string line, address;
    while (std::getline(in, line)) {
      if (line.rfind("block ", 0) == 0) address = line.substr(line.rfind(' ') + 1);
      if (line.rfind("regs ", 0) == 0) vectors += address + ": " + line.substr(5) + "\n";
    }
  }
  std::istringstream in(spec());
  std::string line, words;
  long first = -1, next = -1;
  int examples = 0;
  bool open = false, candidate = false;  // inside a fence; a plain fence of register lines
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      if (open && candidate && first >= 0) {
        ++examples;
        const std::string quoted = std::to_string(first) + ": " + words;
        EXPECT_NE(vectors.find(quoted), std::string::npos)
            << "robot-bridge.md quotes registers that no golden vector has:\n" << quoted;
      }
      candidate = !open && line == "```";
      open = !open;
      first = next = -1;
      words.clear();
      continue;
    }
    if (!open || !candidate) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos || colon == 0 || line.find_first_not_of("0123456789") != colon) {
      candidate = false;  // not a register example
      continue;
    }
    const long address = std::stol(line.substr(0, colon));
    if (first < 0) first = address;
    else EXPECT_EQ(address, next) << "non-contiguous example line: " << line;
    std::istringstream ws(line.substr(colon + 1));
    std::string w;
    while (ws >> w) {
      EXPECT_EQ(w.size(), 4u) << line;
      EXPECT_EQ(w.find_first_not_of("0123456789abcdef"), std::string::npos) << line;
      words += (words.empty() ? "" : " ") + w;
      next = (next < 0 ? address : next) + 1;
    }
  }
  EXPECT_FALSE(open) << "unbalanced ``` fences in robot-bridge.md";
  EXPECT_GE(examples, 3);
}

// §6's table states check.hpp's limits.
TEST(RobotBridgeSpec, CommandTableStatesTheCheckedLimits) {
  const std::string cells[] = {
      "| 1.." + std::to_string(kMaxLinSpeedUmPerS) + " µm/s |",
      "| 1.." + std::to_string(kMaxPtpSpeedPermille) + " ‰ of",
      "| 1.." + std::to_string(kMaxApproachSpeedUmPerS) + " µm/s |",
      "| 1.." + std::to_string(kMaxDigitalInput) + " if the `digital_input` bit is set |",
      "| 1.." + std::to_string(kMaxForceThresholdMN) + " mN if the `force` bit is set |",
      "| −" + std::to_string(kMaxApproachTravelUm) + ".." + std::to_string(kMaxApproachTravelUm) + " µm, ≠ 0 |",
      "| 1.." + std::to_string(kMaxTool) + " |",
      "−" + std::to_string(kMaxAngleMdeg) + ".." + std::to_string(kMaxAngleMdeg) + " mdeg",
  };
  for (const std::string& cell : cells) EXPECT_NE(spec().find(cell), std::string::npos) << cell;
}

TEST(RobotBridgeSpec, RejectionsAreTheResultsFrom32On) {
  for (const EnumValueInfo& v : EnumInfo<Result>::values)
    EXPECT_EQ(v.value >= 32, std::string(v.name).rfind("rejected_", 0) == 0) << v.name;
}

}  // namespace
}  // namespace palp::proto::rb
