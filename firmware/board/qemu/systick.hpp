// SPDX-License-Identifier: Apache-2.0
// SysTick, the Cortex-M4's 24-bit down-counter, used to count instructions under QEMU.
//
// Sources:
//   [ARM] ARMv7-M Architecture Reference Manual (ARM DDI 0403E), B3.3 "The system timer,
//         SysTick": SYST_CSR 0xE000E010 (bit 0 ENABLE, bit 1 TICKINT, bit 2 CLKSOURCE = processor
//         clock, bit 16 COUNTFLAG), SYST_RVR 0xE000E014 (reload, 24 bits), SYST_CVR 0xE000E018
//         (current value; any write clears it), SYST_CALIB 0xE000E01C.
//   [QD]  reference/qemu-icount.md: with `-icount shift=0` every instruction advances virtual
//         time by 1 ns and SysTick with CLKSOURCE=1 runs at 25 MHz, so one SysTick count is
//         exactly 40 instructions, identical on every run.
#pragma once

#include <cstdint>

namespace palp::board::systick {

inline constexpr std::uintptr_t kCsr = 0xE000E010u;  // [ARM] B3.3.3
inline constexpr std::uintptr_t kRvr = 0xE000E014u;  // [ARM] B3.3.4
inline constexpr std::uintptr_t kCvr = 0xE000E018u;  // [ARM] B3.3.5
inline constexpr std::uint32_t kCsrEnable = 1u << 0;      // [ARM] B3.3.3
inline constexpr std::uint32_t kCsrClkSource = 1u << 2;   // [ARM] B3.3.3: processor clock
inline constexpr std::uint32_t kReloadMax = 0x00FFFFFFu;  // [ARM] B3.3.4: 24 bits
inline constexpr std::uint32_t kInstructionsPerCount = 40;  // [QD] under -icount shift=0

inline volatile std::uint32_t& reg(std::uintptr_t a) {
  return *reinterpret_cast<volatile std::uint32_t*>(a);
}

/// Starts the counter from its maximum, counting down on the processor clock, no interrupt.
inline void start() {
  reg(kCsr) = 0;
  reg(kRvr) = kReloadMax;
  reg(kCvr) = 0;
  reg(kCsr) = kCsrEnable | kCsrClkSource;
}

/// The current count (counts down from kReloadMax, wraps after 2^24 counts).
inline std::uint32_t now() { return reg(kCvr) & kReloadMax; }

/// Counts elapsed from `earlier` to `later` readings of now(), for intervals under 2^24 counts.
inline std::uint32_t elapsed(std::uint32_t earlier, std::uint32_t later) {
  return (earlier - later) & kReloadMax;
}

}  // namespace palp::board::systick
