// SPDX-License-Identifier: Apache-2.0
// Cortex-M4 System Control Block registers the boards' startup code uses (QEMU's mps2-an386 and
// the STM32G474 alike: both are ARMv7-M cores, so one definition serves both).
//
// Sources:
//   [ARM] B3.2.5 "Vector Table Offset Register, VTOR": address 0xE000ED08, TBLOFF in [31:7].
//   [ARM] B3.2.6 "Application Interrupt and Reset Control Register, AIRCR": address 0xE000ED0C;
//         a write takes effect only with VECTKEY 0x05FA in [31:16]; SYSRESETREQ (bit 2) asks for
//         a system reset (the STM32G474 board's bootloader entry).
//   [ARM] ARMv7-M Architecture Reference Manual (ARM DDI 0403E), B3.2.20 "Coprocessor Access
//         Control Register, CPACR": address 0xE000ED88; CP10 in bits [21:20], CP11 in [23:22],
//         0b11 = full access. Both must be enabled together for the FPU.
//   [GUG] Cortex-M4 Devices Generic User Guide (ARM DUI 0553), 4.6.1 "Coprocessor Access Control
//         Register": the same, and "Enabling the FPU" (set CP10/CP11, then DSB and ISB).
//   [QD]  reference/qemu-icount.md: mps2-an386 has the FPU; the reset handler must enable it.
#pragma once

#include <cstdint>

namespace palp::board::scb {

inline constexpr std::uintptr_t kVtor = 0xE000ED08u;         // [ARM] B3.2.5
inline constexpr std::uintptr_t kCpacr = 0xE000ED88u;        // [ARM], [GUG]
inline constexpr std::uintptr_t kAircr = 0xE000ED0Cu;        // [ARM] B3.2.6
inline constexpr std::uint32_t kAircrVectKey = 0x05FAu << 16;   // [ARM] B3.2.6
inline constexpr std::uint32_t kAircrSysResetReq = 1u << 2;     // [ARM] B3.2.6
inline constexpr std::uint32_t kCpacrCp10Cp11Full = 0xFu << 20;  // [ARM], [GUG]

inline volatile std::uint32_t& cpacr() {
  return *reinterpret_cast<volatile std::uint32_t*>(kCpacr);
}

inline volatile std::uint32_t& vtor() {
  return *reinterpret_cast<volatile std::uint32_t*>(kVtor);
}

}  // namespace palp::board::scb
