// SPDX-License-Identifier: Apache-2.0
// Exit with a code through ARM semihosting, which QEMU turns into its own exit status.
//
// Source: ARM "Semihosting for AArch32 and AArch64" (ARM-software/abi-aa, semihosting.rst):
//   - on M-profile the semihosting trap is `BKPT 0xAB`, operation number in r0, argument in r1;
//   - SYS_EXIT_EXTENDED is operation 0x20; r1 points to two words {reason, subcode};
//   - reason ADP_Stopped_ApplicationExit is 0x20026, subcode is the exit code.
// reference/qemu-icount.md ("Exit with a code"): QEMU 7.2 with
// `-semihosting-config enable=on,target=native` exits with that code (0-255 tested); the older
// SYS_EXIT (0x18) can report only 0 or 1.
#include <cstdint>

#include "board.hpp"

namespace palp::board {

namespace {
constexpr std::uint32_t kSysExitExtended = 0x20;
constexpr std::uint32_t kAdpStoppedApplicationExit = 0x20026;
}  // namespace

void exit(int code) {
  const std::uint32_t block[2] = {kAdpStoppedApplicationExit, static_cast<std::uint32_t>(code)};
  asm volatile(
      "mov r0, %0\n"
      "mov r1, %1\n"
      "bkpt 0xab\n"
      :
      : "r"(kSysExitExtended), "r"(block)
      : "r0", "r1", "memory");
  for (;;) {  // not reached under QEMU with semihosting; a debugger may resume here
    asm volatile("wfi");
  }
}

}  // namespace palp::board
