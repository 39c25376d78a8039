// SPDX-License-Identifier: Apache-2.0
// The Cortex-M4 NVIC registers both boards use (QEMU's mps2-an386 and the STM32G474 are ARMv7-M
// cores, so one definition serves both): enabling, masking, pending and prioritising single
// external interrupts (the tick guard masks only the control tick's interrupt).
//
// Sources:
//   [ARM] ARMv7-M Architecture Reference Manual (ARM DDI 0403E), B3.4 "Nested Vectored
//         Interrupt Controller, NVIC": NVIC_ISER0 0xE000E100 (write 1 to enable), NVIC_ICER0
//         0xE000E180 (write 1 to disable), NVIC_ISPR0 0xE000E200 (write 1 to set pending),
//         NVIC_ICPR0 0xE000E280 (write 1 to clear pending), one bit per interrupt, 32 per word;
//         NVIC_IPR0 0xE000E400 (one priority byte per interrupt, four per word, lower value =
//         more urgent; an implementation keeps only the top bits, at least 3 on ARMv7-M).
//   [GUG] Cortex-M4 Devices Generic User Guide (ARM DUI 0553), 4.2 "Nested Vectored Interrupt
//         Controller" (the same addresses; the M4 implements at least 3 priority bits) and 4.2.9
//         on the DSB/ISB after disabling an interrupt before relying on it being masked.
//
// The addresses and the bit/byte arithmetic are plain constexpr so a board written against a
// register-access seam (the STM32G474's, tests on a host register file) uses the same
// definitions; the direct volatile accessors below them are for code that runs on the core only.
#pragma once

#include <cstdint>

namespace palp::board::nvic {

inline constexpr std::uint32_t kIser0 = 0xE000E100u;  // [ARM] B3.4.4
inline constexpr std::uint32_t kIcer0 = 0xE000E180u;  // [ARM] B3.4.5
inline constexpr std::uint32_t kIspr0 = 0xE000E200u;  // [ARM] B3.4.6
inline constexpr std::uint32_t kIcpr0 = 0xE000E280u;  // [ARM] B3.4.7
inline constexpr std::uint32_t kIpr0 = 0xE000E400u;   // [ARM] B3.4.9

/// The word of a one-bit-per-interrupt register (ISER/ICER/ISPR/ICPR) that holds `irq`, given
/// the register's first word, and the bit to write there [ARM] B3.4.4..7.
constexpr std::uint32_t bit_word(std::uint32_t first_word, std::uint32_t irq) {
  return first_word + 4u * (irq / 32u);
}
constexpr std::uint32_t bit_of(std::uint32_t irq) { return 1u << (irq % 32u); }
/// The IPR word holding `irq`'s priority byte, and that byte's shift in it [ARM] B3.4.9.
constexpr std::uint32_t priority_word(std::uint32_t irq) { return kIpr0 + 4u * (irq / 4u); }
constexpr std::uint32_t priority_shift(std::uint32_t irq) { return 8u * (irq % 4u); }

/// Priorities used by the boards, in the top 2 bits so that any implemented width keeps them
/// distinct [ARM], [GUG]: lower is more urgent.
inline constexpr std::uint8_t kPriorityClock = 0x00;  // a clock's wrap count: never waits
inline constexpr std::uint8_t kPriorityTick = 0x40;   // the control tick
inline constexpr std::uint8_t kPriorityLink = 0x80;   // the host link's receive / transmit

#if defined(__arm__)
inline volatile std::uint32_t& word(std::uint32_t a) {
  return *reinterpret_cast<volatile std::uint32_t*>(static_cast<std::uintptr_t>(a));
}

inline void set_priority(std::uint32_t irq, std::uint8_t priority) {
  *reinterpret_cast<volatile std::uint8_t*>(static_cast<std::uintptr_t>(kIpr0 + irq)) = priority;
}
inline void enable(std::uint32_t irq) { word(bit_word(kIser0, irq)) = bit_of(irq); }
/// Disables the interrupt; after the DSB/ISB it can no longer be taken [GUG] 4.2.9.
inline void disable(std::uint32_t irq) {
  word(bit_word(kIcer0, irq)) = bit_of(irq);
  asm volatile("dsb\n isb" ::: "memory");
}
inline void set_pending(std::uint32_t irq) { word(bit_word(kIspr0, irq)) = bit_of(irq); }
inline void clear_pending(std::uint32_t irq) { word(bit_word(kIcpr0, irq)) = bit_of(irq); }
#endif

}  // namespace palp::board::nvic
