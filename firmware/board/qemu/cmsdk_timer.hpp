// SPDX-License-Identifier: Apache-2.0
// CMSDK APB timers of QEMU's mps2-an386: the control tick (timer 0) and the free-running clock
// (timer 1).
//
// Sources:
//   [TRM] ARM Cortex-M System Design Kit Technical Reference Manual, ARM DDI 0479C, chapter 4
//         "APB Components", section "APB timer": a 32-bit down-counter; CTRL 0x00 (bit 0 enable,
//         bit 1 external input as enable, bit 2 external input as clock, bit 3 interrupt
//         enable), VALUE 0x04, RELOAD 0x08, INTSTATUS/INTCLEAR 0x0C (bit 0, write 1 to clear).
//   [QT]  QEMU hw/timer/cmsdk-apb-timer.c: the same registers; the interrupt is raised when the
//         count goes from 1 to 0, the count holds 0 for one clock and then reloads, so a periodic
//         timer's period is RELOAD + 1 clocks; writing RELOAD also sets VALUE; RELOAD 0 stops it.
//   [QM]  QEMU hw/arm/mps2.c (AN385/AN386/AN500 machines): timer 0 at 0x40000000 on IRQ 8,
//         timer 1 at 0x40001000 on IRQ 9, both clocked at SYSCLK_FRQ = 25 MHz;
//         reference/qemu-icount.md "The machine" (25 MHz system clock, timer addresses).
#pragma once

#include <cstdint>

namespace palp::board::cmsdk_timer {

inline constexpr std::uintptr_t kTimer0Base = 0x40000000u;  // [QM]
inline constexpr std::uintptr_t kTimer1Base = 0x40001000u;  // [QM]
inline constexpr std::uint32_t kTimer0Irq = 8;              // [QM]
inline constexpr std::uint32_t kTimer1Irq = 9;              // [QM]
inline constexpr std::uint32_t kClock_Hz = 25'000'000u;     // [QM] SYSCLK_FRQ

// Register offsets [TRM], [QT].
inline constexpr std::uintptr_t kCtrl = 0x00;
inline constexpr std::uintptr_t kValue = 0x04;
inline constexpr std::uintptr_t kReload = 0x08;
inline constexpr std::uintptr_t kIntStatus = 0x0C;  // read: status; write 1: clear

// CTRL bits [TRM], [QT].
inline constexpr std::uint32_t kCtrlEnable = 1u << 0;
inline constexpr std::uint32_t kCtrlIrqEnable = 1u << 3;

inline constexpr std::uint32_t kIntStatusIrq = 1u << 0;  // [TRM], [QT]

/// RELOAD for a periodic interrupt every `clocks` timer clocks ([QT]: the period is RELOAD + 1).
inline constexpr std::uint32_t reload_for_period(std::uint32_t clocks) { return clocks - 1u; }

inline volatile std::uint32_t& reg(std::uintptr_t base, std::uintptr_t offset) {
  return *reinterpret_cast<volatile std::uint32_t*>(base + offset);
}

}  // namespace palp::board::cmsdk_timer
