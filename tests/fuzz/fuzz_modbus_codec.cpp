// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the robot bridge's register codec (protocol/robot-bridge.md): the input
// as big-endian 16-bit registers, decoded as each block and checked as a command (§3), as the
// bridge and the robot client do with registers from the wire. Properties:
//  - nothing crashes or reads out of bounds (ASan/UBSan watch);
//  - a block that decodes re-encodes to registers that decode to the same registers again;
//  - a command block accepted by check_command is accepted again after encoding it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "palp/protocol/robot_bridge/check.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"

namespace {

using namespace palp::proto;
using namespace palp::proto::rb;

[[noreturn]] void fail() { __builtin_trap(); }

template <class B>
void round_trip(std::span<const u16> all) {
  if (all.size() < B::kLength) return;
  const std::span<const u16> regs = all.first(B::kLength);
  B b{};
  if (!decode(regs, b).ok()) return;
  u16 first[B::kLength];
  encode(b, std::span<u16, B::kLength>(first));
  B again{};
  if (!decode(std::span<const u16>(first, B::kLength), again).ok()) fail();
  u16 second[B::kLength];
  encode(again, std::span<u16, B::kLength>(second));
  for (u16 k = 0; k < B::kLength; ++k)
    if (first[k] != second[k]) fail();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<u16> regs(size / 2);
  for (std::size_t k = 0; k < regs.size(); ++k)
    regs[k] = static_cast<u16>(data[2 * k] << 8 | data[2 * k + 1]);
  const std::span<const u16> in(regs);
#define PALP_FUZZ_BLOCK(Name, ...) round_trip<Name>(in);
  PALP_RB_BLOCKS(PALP_FUZZ_BLOCK)
#undef PALP_FUZZ_BLOCK
  if (in.size() >= Command::kLength) {
    Command c{};
    if (check_command(in.first(Command::kLength), c).accepted()) {
      u16 again[Command::kLength];
      encode(c, std::span<u16, Command::kLength>(again));
      Command d{};
      if (!check_command(std::span<const u16>(again, Command::kLength), d).accepted() || !(c == d))
        fail();
    }
  }
  return 0;
}
